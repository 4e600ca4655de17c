#pragma once
// A triangle 2-complex (edges may bound any number of triangles) with the adjacency that the
// Erosion Thickness algorithms need: unique edges, edge -> triangles, vertex -> triangles and,
// per triangle, which edge each side is and where the triangle sits in that edge's list (the
// "triangle -> edge-slot" map of the implementation notes, §4).
//
// Corner convention: triangle t = (c0, c1, c2); side j joins c_j and c_{j+1 mod 3} and is
// opposite corner c_{j+2 mod 3}. Edges are stored with a < b.
#include <medax/geometry.hpp>

#include <cstdint>
#include <vector>

namespace medax::et {

inline constexpr Index kNone = 0xffffffffu;

struct TriangleComplex {
  std::vector<Vec3> points;
  std::vector<double> radii;
  std::vector<Tri> triangles;

  std::vector<Segment> edges;                          ///< unique, a < b
  std::vector<std::array<Index, 3>> tri_edges;         ///< edge id of side j
  std::vector<std::array<Index, 3>> tri_edge_slot;     ///< position of t in edge_tris of side j
  std::vector<Index> edge_tri_begin, edge_tris;        ///< CSR: edge -> triangles (ascending)
  std::vector<Index> vert_tri_begin, vert_tris;        ///< CSR: vertex -> triangles (ascending)

  std::size_t num_vertices() const { return points.size(); }
  std::size_t num_edges() const { return edges.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  Index edge_degree(Index e) const { return edge_tri_begin[e + 1] - edge_tri_begin[e]; }
  Index vertex_degree(Index v) const { return vert_tri_begin[v + 1] - vert_tri_begin[v]; }
  /// True when side j of t runs from the edge's first vertex to its second.
  bool side_forward(Index t, int j) const { return triangles[t][j] == edges[tri_edges[t][j]][0]; }
  /// Length of the longest side of the bounding box of the points (0 when empty).
  double max_bbox_side() const;
};

/// Builds the adjacency. Triangles with a repeated corner are rejected with
/// std::invalid_argument (clean the complex first: `pure_complex`); duplicate triangles are
/// kept as given (each is its own sheet piece).
TriangleComplex build_triangle_complex(std::vector<Vec3> points, std::vector<double> radii,
                                       std::vector<Tri> triangles);

/// Sectors of a vertex (§3 of the notes): the components of its star's manifold part. Triangles
/// around v that share an edge of degree 2 are in one sector; a sector is a chain of triangles
/// whose two ends are link nodes (edges v-w) of degree != 2, or a closed chain. The compressed
/// link graph H_v has one node per link node of degree != 2 and one edge per sector (a
/// self-loop for closed chains or chains that end twice on the same link node).
struct VertexSectors {
  /// Per corner (3 t + j): the local sector index at vertex triangles[t][j].
  std::vector<std::uint16_t> corner_sector;
  /// CSR per vertex: sectors [sector_begin[v], sector_begin[v+1]).
  std::vector<Index> sector_begin;
  /// Per sector: its two ends in H_v (local node ids), equal for a self-loop.
  std::vector<std::uint16_t> end_a, end_b;
  /// Per vertex: number of H_v nodes.
  std::vector<std::uint16_t> h_nodes;
  /// Per vertex: H_v is a forest (every sector exposed when all are unburned): v is on ∂G.
  std::vector<char> boundary;
};

VertexSectors compute_vertex_sectors(const TriangleComplex& cx);

}  // namespace medax::et
