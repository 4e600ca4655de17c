#pragma once
// Medial curves (Yan et al. 2016, §7.1-7.2; notes §5): every triangle is cut by the burn-tree
// arcs that lie in it into faces; the medial curves C are the dual graph (one vertex per face,
// one per edge segment between consecutive graph nodes, an edge from a face to each segment on
// its boundary) with the burn-time-weighted dual positions of the paper, and ET_C = BT_C - BT_M
// by the 1D burn.
//
// Points of the subdivision share one id space: graph nodes [0, N), segment duals [N, N + S),
// face duals [N + S, N + S + F). Segment q of edge e joins edge-nodes q and q+1, where edge-node
// 0 is edges[e][0], edge-node n+1 is edges[e][1] and edge-nodes 1..n are its samples.
//
// Precisely, C is the order complex of the cells that survive cutting M along the burn forest
// and removing the burned nodes: faces (open 2-cells), segments (open 1-cells) and unburned
// nodes, related by "lies on the boundary of". Without closed surfaces every node burns and this
// is the paper's graph: an edge from each face to each segment on its boundary, except
//   - a segment covered by a burn-tree edge-arc of the same triangle (the notes' zero-area
//     digon, read as "the arc sits just inside the triangle": the face does not reach the
//     segment there; the digon itself would only add a leaf, so it is not built);
//   - a segment on ∂M (edge with one triangle), a leaf that the notes skip, unless the face has
//     no other connection.
// On closed surfaces that never burn (BT = inf), the unburned nodes are cells too: the complex
// gets face-node and segment-node edges and the triangles (face, segment, node), i.e. the
// closed surfaces appear barycentrically subdivided and the curves attach to them without
// spurious cycles, so C stays homotopy equivalent to M (b2 included).
// Where the cut splits off a piece that only a burn arc or a node connects to the rest (an arc
// between two ∂M nodes, two sheets touching at a vertex), C gets a bridge face - node - face, only
// between different components, so no cycle is added (`bridges` counts them).
#include "burn.hpp"
#include "burn_1d.hpp"

#include <vector>

namespace medax::et {

struct Subdivision {
  Index num_nodes = 0, num_segments = 0;
  std::vector<Index> segment_begin;  ///< per edge (+1): first segment id; edge e has n_e + 1

  // Faces, contiguous per triangle.
  std::vector<Index> tri_face_begin;  ///< per triangle (+1)
  std::vector<Index> face_tri;
  std::vector<Index> face_begin;      ///< per face (+1): range in corners / side_segment / side_covered
  std::vector<Index> corners;         ///< node ids around the face
  std::vector<Index> side_segment;    ///< side (corner k -> k+1): segment id, or kNone for a chord
  std::vector<char> side_covered;     ///< side is a segment covered by a burn-tree edge-arc of this triangle
  std::vector<Index> side_chord;      ///< side is a chord (burn arc across the triangle): its id, else kNone
  Index num_chords = 0;
  std::vector<char> face_residue;     ///< all corners unburned (a triangle of a closed surface)

  // Dual points.
  std::vector<char> segment_used;     ///< the segment has a dual point (some face connects to it)
  std::vector<Vec3> point;            ///< per point id (nodes, segment duals, face duals)
  std::vector<double> point_bt;       ///< BT_M (inf when unburned)
  std::vector<double> point_radius;   ///< R (linear interpolation)
  std::vector<double> point_et;       ///< ET_M = BT_M - R (inf when unburned)

  // The medial curves: edges (face dual, segment dual), and with closed surfaces also
  // (face, unburned node), (segment, unburned node) edges and (face, segment, node) triangles.
  std::vector<Segment> curve_edges;   ///< global point ids
  std::vector<Tri> curve_triangles;   ///< global point ids (only with closed surfaces)

  std::size_t crossing_arcs = 0;      ///< burn arcs dropped because they crossed another (round-off)
  std::size_t unconnected_faces = 0;  ///< faces with no side to connect (should not happen)
  std::size_t residue_triangles = 0;
  std::size_t bridges = 0;            ///< components of C joined again (see build_subdivision)

  Index num_faces() const { return static_cast<Index>(face_tri.size()); }
  Index segment_point(Index s) const { return num_nodes + s; }
  Index face_point(Index f) const { return num_nodes + num_segments + f; }
  std::size_t num_points() const { return point.size(); }
  /// Nodes of segment s (global node ids).
  std::array<Index, 2> segment_nodes(const BurnGraph& g, Index s) const;
};

Subdivision build_subdivision(const BurnGraph& g, const BurnResult& burn);

/// The medial curves with per-vertex BT_M, BT_C and ET_C. `source` maps each vertex to its point
/// id in the subdivision. `faces` is empty unless the complex has closed surfaces.
struct MedialCurves {
  std::vector<Vec3> points;
  std::vector<double> radius, bt_m, bt_c, et_c;
  std::vector<Index> source;
  std::vector<int> kind;  ///< 0 graph vertex, 1 edge sample, 2 segment dual, 3 face dual
  std::vector<Segment> edges;
  std::vector<Tri> faces;
};

/// ET_C per subdivision point (+inf on cycles and closed surfaces; NaN for points off C).
std::vector<double> curve_erosion_thickness(const Subdivision& sub, std::vector<double>* bt_c = nullptr);

MedialCurves extract_medial_curves(const BurnGraph& g, const Subdivision& sub);

/// The boundary of face f with the used segment duals inserted: point ids in order.
void face_boundary_points(const Subdivision& sub, Index f, std::vector<Index>& out);

}  // namespace medax::et
