#pragma once
// The medial mesh M of the Medial Skeletal Diagram (Guo et al. 2024, notes §2.1, §3 S1–S2, §4):
// a non-manifold complex of triangle facets and dangling edges, with the incidence maps the
// construction needs, graph distances on its vertex graph and closest-point projection onto it.
#include <medax/medial_complex.hpp>

#include <memory>
#include <optional>
#include <vector>

namespace medax::msd {

/// A point of M: its position and the facet that holds it. Facets are numbered triangles first
/// (0 .. T-1), then dangling edges (T .. T+D-1); see MedialMesh::is_triangle_facet.
struct MeshPoint {
  Vec3 point = Vec3::Zero();
  Index facet = 0;
  double distance = 0;  ///< distance from the queried point (closest_point only)
};

class MedialMesh {
 public:
  /// M from a medial complex: vertices closer than `merge_tolerance` (absolute) are merged,
  /// degenerate and repeated elements dropped, only the largest connected component is kept
  /// (by vertex count; ties to the one holding the lowest vertex), unused vertices removed.
  static MedialMesh from_complex(const MedialComplex& complex, double merge_tolerance = 0);

  /// M as given (indices must be valid; no cleaning). Edges that are sides of a triangle are
  /// ignored as dangling edges.
  MedialMesh(std::vector<Vec3> points, std::vector<Tri> triangles, std::vector<Segment> edges);
  ~MedialMesh();
  MedialMesh(MedialMesh&&) noexcept;
  MedialMesh& operator=(MedialMesh&&) noexcept;

  const std::vector<Vec3>& points() const { return points_; }
  const std::vector<Tri>& triangles() const { return triangles_; }
  const std::vector<Segment>& dangling_edges() const { return dangling_; }
  /// Every distinct edge (triangle sides and dangling edges), each as (low, high), sorted.
  const std::vector<Segment>& edges() const { return edges_; }

  std::size_t num_facets() const { return triangles_.size() + dangling_.size(); }
  bool is_triangle_facet(Index facet) const { return facet < triangles_.size(); }
  /// The vertices of a facet (2 for a dangling edge, 3 for a triangle).
  std::vector<Index> facet_vertices(Index facet) const;

  /// Index into edges() of edge {a, b}, if it exists.
  std::optional<Index> edge_index(Index a, Index b) const;
  /// Facets (triangles and the dangling edge itself) incident to edge e.
  const std::vector<Index>& edge_facets(Index e) const { return edge_facets_[e]; }
  /// Facets incident to vertex v.
  const std::vector<Index>& vertex_facets(Index v) const { return vertex_facets_[v]; }
  /// Facets sharing an edge with `facet` (facet adjacency), sorted.
  const std::vector<Index>& facet_neighbours(Index facet) const { return facet_neighbours_[facet]; }
  /// The edge indices (into edges()) of a facet's sides.
  std::vector<Index> facet_edges(Index facet) const;

  /// Shortest-path (Dijkstra) distance between vertices on M's vertex graph, edges weighted by
  /// length. All pairs (distances and predecessors, 12 bytes a pair: 48 MB at the limit) are
  /// cached at construction when |V| <= kAllPairsLimit; above it each query runs Dijkstra.
  double distance(Index a, Index b) const;
  /// Graph distances from one vertex to all.
  std::vector<double> distances_from(Index source) const;
  /// The vertices of a shortest path from a to b, both included (a alone when a == b).
  std::vector<Index> shortest_path(Index a, Index b) const;

  /// The closest point of M (triangles and dangling edges) to p.
  MeshPoint closest_point(const Vec3& p) const;

  static constexpr std::size_t kAllPairsLimit = 2000;

 private:
  void build_incidence();
  void build_distances();
  struct Tree;
  std::vector<Vec3> points_;
  std::vector<Tri> triangles_;
  std::vector<Segment> dangling_;
  std::vector<Segment> edges_;
  std::vector<std::vector<Index>> edge_facets_, vertex_facets_, facet_neighbours_;
  std::vector<std::vector<std::pair<Index, double>>> adjacency_;  ///< vertex graph
  std::vector<double> all_distances_;                              ///< |V|² or empty
  std::vector<Index> all_predecessors_;                            ///< |V|² or empty
  std::unique_ptr<Tree> tree_;
};

/// Farthest-point selection on M's graph distances (notes S2): starts at vertex `start` and
/// adds, k-1 times, the vertex whose smallest distance to the chosen ones is largest (ties to
/// the lowest index). Returns min(k, |V|) vertex indices.
std::vector<Index> farthest_point_sites(const MedialMesh& mesh, std::size_t k, Index start = 0);

}  // namespace medax::msd
