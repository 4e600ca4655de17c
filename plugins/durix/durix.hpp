#pragma once
// Durix, Leonard, Chambon, Morin 2023, "A clean, robust 3D medial axis": the interior medial
// axis of a Delaunay surface mesh, propagated sheet by sheet from a seed over the interior
// Delaunay cells, with ε-significance tests on the singular paths, carving of insignificant
// regions out of a working surface M_w, a fixpoint, and splitting at problematic edges.
//
// The output medial complex is exactly dual to M_w: its vertices are the interior Delaunay cells
// of M_w's vertices, its edges the interior non-surface facets, its faces the Voronoi polygons of
// the interior edges (fan-triangulated for MedialComplex).
#include "significance.hpp"

#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <array>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace medax::durix {

/// Edge labels `path_type` of the output complex.
enum PathType : int {
  kFanDiagonal = -1,  ///< a diagonal of a fan-triangulated Voronoi face (not a Voronoi edge)
  kCurve = 0,         ///< degree 0: an edge of a one-dimensional sheet
  kBoundary = 1,      ///< degree 1: on a boundary path
  kRegular = 2,       ///< degree 2: inside a sheet
  kSingular = 3,      ///< degree 3, or degree 2 between faces of different sheets: on a singular path
  kForcedSingular = 4,  ///< degree 2 made singular to split a sheet at problematic edges (§3.8)
  kProblematic = 5,   ///< degree 3 with its three faces on one sheet (left when splitting failed)
};

/// The label columns of the output complex (docs/plugins/durix.md, Output).
inline const Property<int> kNodeType{Element::Vertex, "node_type"};  ///< 1 boundary, 2 regular, 3 singular
inline const Property<int> kNodeSheet{Element::Vertex, "sheet"};     ///< -1: several sheets or none
inline const Property<int> kNodeFlat{Element::Vertex, "flat"};       ///< 1: a flat cell
inline const Property<int> kPathType{Element::Edge, "path_type"};    ///< a PathType
inline const Property<int> kEdgeDegree{Element::Edge, "degree"};     ///< Voronoi faces around it; -1 diagonal
inline const Property<int> kEdgeSheet{Element::Edge, "sheet"};       ///< -1 on singular edges
inline const Property<int> kFaceSheet{Element::Face, "sheet"};
inline const Property<int> kVoronoiFace{Element::Face, "voronoi_face"};  ///< the Voronoi polygon
inline const Property<int> kGeneratorA{Element::Face, "generator_a"};    ///< the DT edge of the polygon
inline const Property<int> kGeneratorB{Element::Face, "generator_b"};

struct DurixOptions {
  /// Refuse a carving that would change the Euler characteristic of M_w (notes §3.5 `closable`
  /// filter, as a topological test). false: a region covered within ε is removed even when
  /// that closes a handle.
  bool preserve_topology = true;
  /// Remove boundary spikes covered within ε (notes §3.7).
  bool simplify_boundaries = true;
  /// Appendix A: carve cells at the surface whose ball is centred outside the input (ε-tested).
  bool remove_outside_centres = true;
  /// Split sheets at problematic edges (notes §3.8).
  bool split_problematic = true;
  /// Fixpoint: repeat propagation and carving until a pass removes nothing (at most this many).
  int max_passes = 10;
};

struct DurixReport {
  std::size_t input_vertices = 0, input_faces = 0;
  std::size_t dt_cells = 0, interior_cells = 0, components = 0;
  int passes = 0;
  std::size_t candidates = 0;            ///< neighbour sheets tested
  std::size_t removals = 0;              ///< regions carved (main loop)
  std::size_t boundary_removals = 0;     ///< boundary spikes carved (§3.7)
  std::size_t flat_cells_peeled = 0;     ///< flat surface cells removed (Appendix A)
  std::size_t leaves_pruned = 0;         ///< curve ends carved (1D boundary simplification)
  std::size_t outside_centres_removed = 0;  ///< cells with an outside centre carved (Appendix A)
  std::size_t outside_centres_left = 0;  ///< output nodes whose centre is outside the input
  std::size_t rejected_not_separated = 0;  ///< region reaches the computed skeleton
  std::size_t rejected_manifold = 0;     ///< carving would make M_w non-manifold
  std::size_t rejected_topology = 0;     ///< carving would change χ(M_w)
  std::size_t path_failures = 0;         ///< singular paths that did not close
  std::size_t removed_vertices = 0;      ///< input vertices no longer on M_w
  std::size_t problematic_edges = 0;     ///< found before splitting
  std::size_t problematic_left = 0;      ///< left after splitting
  std::size_t forced_edges = 0;          ///< regular edges made singular by §3.8
  std::size_t sheets = 0, curve_sheets = 0;
  /// Path census of the final labelling (notes §5.5): half-paths followed, how many did not
  /// close, corner changes not across an M_w edge, boundary edges not traced exactly twice.
  std::size_t singular_paths = 0, boundary_paths = 0, unclosed_paths = 0, loop_corner_errors = 0,
              boundary_multiplicity_errors = 0;
  std::size_t nodes = 0, medial_edges = 0, medial_faces = 0;
  std::size_t surface_vertices = 0, surface_faces = 0;
  double epsilon = 0;
  /// Over removed input vertices: min over the witness node and the 16 nodes nearest to it of
  /// (‖v − c‖ − r): an upper bound of the distance to the union of the output balls, ≤ ε by
  /// construction (each removed vertex keeps a witness ball covering it within ε).
  double max_removed_excess = 0;
  double seconds_dual = 0, seconds_propagation = 0, seconds_problematic = 0, seconds_output = 0;
};

struct DurixResult {
  MedialComplex medial;
  /// M_w: the working surface after carving, compact (only its own vertices), outward.
  SurfaceMesh surface;
  std::vector<Index> surface_vertex;     ///< M_w vertex -> input vertex
  std::vector<Index> surface_face_node;  ///< M_w face -> medial vertex (its interior cell)
  std::vector<int> surface_face_sheet;   ///< M_w face -> sheet
  /// Segmentation of the input mesh (notes §1.4 voting): sheet per input vertex and face.
  std::vector<int> vertex_sheet, face_sheet;
  /// Input vertex -> a medial vertex: one of its cells when on M_w, its witness when removed.
  std::vector<Index> vertex_node;
  std::vector<char> vertex_removed;  ///< input vertex is no longer on M_w
  DurixReport report;
};

using ProgressFn = std::function<void(double, std::string_view)>;
using CancelFn = std::function<void()>;

/// Computes the medial axis of a Delaunay mesh (closed, outward; throws std::invalid_argument
/// when it is not a Delaunay mesh, with what to do).
DurixResult durix_medial_axis(const SurfaceMesh& mesh, const RegionOracle& oracle, const DurixOptions& options = {},
                              const ProgressFn& progress = {}, const CancelFn& check_cancelled = {});

/// Writes the segmentation of `mesh` (the mesh the result was computed on) as ASCII PLY, its
/// vertices mapped by `frame`: vertices with `red green blue sheet removed node`, faces with
/// `red green blue sheet`.
void write_segmentation_ply(std::ostream& out, const SurfaceMesh& mesh, const DurixResult& result,
                            const Similarity& frame = {});
/// Writes M_w as ASCII PLY, its vertices mapped by `frame`: vertices with `input_index`, faces
/// with `red green blue node sheet`.
void write_surface_ply(std::ostream& out, const DurixResult& result, const Similarity& frame = {});
/// A stable, well-spread colour for a label (grey for -1).
std::array<int, 3> label_colour(int label);

}  // namespace medax::durix
