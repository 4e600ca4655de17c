#pragma once
// Erosion Thickness on a triangulated medial axis (Yan et al. 2016, §6): the sampled graph
// G = (N, A) and algorithm Burn (Fig. 8, as restored in the implementation notes §4).
//
// Nodes: the complex's vertices (ids 0..V-1), then max(min_samples, floor(l/omega)) uniformly
// spaced samples on every edge of length l (edge e's samples are ids
// sample_begin[e] .. sample_begin[e+1]-1, ordered from edges[e][0] to edges[e][1]). Arcs are
// never stored: a triangle-arc joins two nodes of one triangle that are not on a common side,
// an edge-arc joins two consecutive nodes of a side, one per incident triangle; an arc is
// identified by its two nodes and its triangle. Each arc lies in exactly one sector at each end.
#include "triangle_complex.hpp"

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace medax::et {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct BurnGraph {
  const TriangleComplex* cx = nullptr;
  VertexSectors vsec;

  std::vector<Index> sample_begin;  ///< per edge (+1): first sample node id
  std::vector<Index> sample_edge;   ///< per sample (node - V): its edge
  std::vector<Vec3> pos;            ///< per node
  std::vector<double> radius;       ///< per node (linear along edges)
  std::vector<Index> sector_begin;  ///< CSR per node (+1): global sector ids
  std::vector<char> boundary;       ///< per node: ∂G (H_v is a forest)

  std::size_t num_nodes() const { return pos.size(); }
  std::size_t num_sectors() const { return sector_begin.back(); }
  Index num_vertices() const { return static_cast<Index>(cx->num_vertices()); }
  bool is_vertex(Index n) const { return n < num_vertices(); }
  Index samples_on(Index e) const { return sample_begin[e + 1] - sample_begin[e]; }
  /// The node at position k (0..n+1) along side j of triangle t, from corner j to corner j+1.
  Index side_node(Index t, int j, Index k) const;
  /// Local sector (at node n) containing triangle t; n must be a node of t.
  Index local_sector(Index n, Index t) const;
  /// Number of arcs (triangle-arcs + one edge-arc per side segment per triangle).
  std::size_t count_arcs() const;
};

/// Builds G. `omega` is absolute (the maximal spacing of nodes on an edge); `min_samples` is
/// the least number of samples per edge (the paper requires 1).
BurnGraph build_burn_graph(const TriangleComplex& cx, double omega, int min_samples);

/// Calls f(u, t) for every arc (n, u) of triangle t, for every triangle t that contains n.
template <typename F>
void for_each_arc(const BurnGraph& g, Index n, F&& f);

struct BurnResult {
  std::vector<double> bt;          ///< per node: BT_G, +inf when never burned
  std::vector<Index> prime_node;   ///< per sector: other end of its primary arc, or kNone
  std::vector<Index> prime_tri;    ///< per sector: triangle of its primary arc, or kNone
  std::vector<Index> burn_order;   ///< nodes in the order they burned
  std::size_t pops = 0, relaxations = 0;
};

/// Algorithm Burn. `cancel` (optional) is called now and then and may throw to stop.
BurnResult burn(const BurnGraph& g, const std::function<void()>& cancel = {});

/// ET_G = BT_G - R per node.
std::vector<double> erosion_thickness(const BurnGraph& g, const BurnResult& r);

// ---- inline ---------------------------------------------------------------------------------

inline Index BurnGraph::side_node(Index t, int j, Index k) const {
  const Tri& f = cx->triangles[t];
  const Index e = cx->tri_edges[t][j];
  const Index n = samples_on(e);
  if (k == 0) return f[j];
  if (k == n + 1) return f[(j + 1) % 3];
  return cx->side_forward(t, j) ? sample_begin[e] + (k - 1) : sample_begin[e] + (n - k);
}

inline Index BurnGraph::local_sector(Index n, Index t) const {
  const Tri& f = cx->triangles[t];
  if (is_vertex(n)) {
    const int j = f[0] == n ? 0 : f[1] == n ? 1 : 2;
    return vsec.corner_sector[3 * t + j];
  }
  const Index e = sample_edge[n - num_vertices()];
  if (cx->edge_degree(e) <= 2) return 0;
  const auto& te = cx->tri_edges[t];
  const int j = te[0] == e ? 0 : te[1] == e ? 1 : 2;
  return cx->tri_edge_slot[t][j];
}

template <typename F>
void for_each_arc(const BurnGraph& g, Index n, F&& f) {
  const TriangleComplex& cx = *g.cx;
  if (g.is_vertex(n)) {
    for (Index i = cx.vert_tri_begin[n]; i < cx.vert_tri_begin[n + 1]; ++i) {
      const Index t = cx.vert_tris[i];
      const Tri& c = cx.triangles[t];
      const int j = c[0] == n ? 0 : c[1] == n ? 1 : 2;
      const int jn = (j + 1) % 3, jp = (j + 2) % 3;
      // Edge-arcs: the next node along side j, the previous along side j+2.
      f(g.side_node(t, j, 1), t);
      f(g.side_node(t, jp, g.samples_on(cx.tri_edges[t][jp])), t);
      // Triangle-arcs: the samples of the opposite side.
      const Index eo = cx.tri_edges[t][jn];
      for (Index s = g.sample_begin[eo]; s < g.sample_begin[eo + 1]; ++s) f(s, t);
    }
    return;
  }
  const Index V = g.num_vertices();
  const Index e = g.sample_edge[n - V];
  const Index ns = g.samples_on(e), p = n - g.sample_begin[e];  // 0-based from edges[e][0]
  const Index prev = p == 0 ? cx.edges[e][0] : n - 1;
  const Index next = p + 1 == ns ? cx.edges[e][1] : n + 1;
  for (Index i = cx.edge_tri_begin[e]; i < cx.edge_tri_begin[e + 1]; ++i) {
    const Index t = cx.edge_tris[i];
    const auto& te = cx.tri_edges[t];
    const int j = te[0] == e ? 0 : te[1] == e ? 1 : 2;
    f(prev, t);
    f(next, t);
    f(cx.triangles[t][(j + 2) % 3], t);
    for (int d = 1; d <= 2; ++d) {
      const Index eo = te[(j + d) % 3];
      for (Index s = g.sample_begin[eo]; s < g.sample_begin[eo + 1]; ++s) f(s, t);
    }
  }
}

}  // namespace medax::et
