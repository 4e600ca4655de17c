#pragma once
// Internal to et_skeleton: the refined cell complex K of the skeleton (skeleton.hpp) and its
// construction from the subdivision.
#include "skeleton.hpp"

#include <limits>
#include <vector>

namespace medax::et::skeleton {

inline constexpr double kNegInf = -std::numeric_limits<double>::infinity();

/// The refined cell complex K (skeleton.hpp). 0-cells are the subdivision's points; 1-cells are,
/// in id order, the segment pieces, the chords, the spokes (face by face) and the loose edges.
struct CellComplex {
  // 1-cells.
  std::vector<Segment> ends;        ///< per 1-cell: its two points
  std::vector<char> curve;          ///< per 1-cell: 1 on the medial curves
  std::vector<Index> piece_base;    ///< per segment (+1): its first piece (two when its dual point is used)
  Index chord_base = 0;             ///< first chord
  std::vector<Index> spoke_begin;   ///< CSR per face (+1) into spoke_target
  std::vector<Index> spoke_target;  ///< the points a face's spokes reach
  // 2-cells: the wedges. Wedge w covers ring positions w_first .. w_first + w_len (cyclic) of its face.
  std::vector<Index> w_face, w_first, w_len;
  std::vector<Index> w_bnd_begin{0}, w_bnd;  ///< boundary 1-cells, with multiplicity
  std::vector<double> w_area;
  std::vector<Index> face_wedge_begin;       ///< per face (+1)
  // Priorities.
  std::vector<double> face_prio;  ///< per face: mean ET_M over its graph-node corners
  std::vector<double> cell_prio;  ///< per 1-cell: mean ET_C of its ends on the curves, else -inf
  // Incidences.
  std::vector<Index> cof_begin, cof;  ///< 1-cell -> wedges (with multiplicity)
  std::vector<Index> inc_begin, inc;  ///< point -> 1-cells

  std::size_t num_cells() const { return ends.size(); }
  std::size_t num_wedges() const { return w_face.size(); }
};

CellComplex build_cell_complex(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                               const std::vector<double>& et_c);

}  // namespace medax::et::skeleton
