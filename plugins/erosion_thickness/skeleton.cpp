#include "skeleton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

namespace medax::et {

namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index(0)); }
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

double mean_of(double a, double b) {
  if (std::isinf(a) && a > 0) return a;
  if (std::isinf(b) && b > 0) return b;
  return 0.5 * (a + b);
}

struct Pair {
  int phase;  // 0: neither cell is a medial-curve edge; 1: one is (those go last)
  double prio_tau, prio_sigma;
  int type;  // 0: (edge, triangle), 1: (vertex, edge)
  Index sigma, tau;
};
struct PairLater {
  bool operator()(const Pair& a, const Pair& b) const {
    return std::tie(a.phase, a.prio_tau, a.prio_sigma, a.type, a.tau, a.sigma) >
           std::tie(b.phase, b.prio_tau, b.prio_sigma, b.type, b.tau, b.sigma);
  }
};

}  // namespace

Skeleton compute_skeleton(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                          const SkeletonOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const std::size_t np = sub.num_points();
  const Index V = g.num_vertices();
  const std::vector<double> et_c = curve_erosion_thickness(sub);

  // ---- K: fan triangles per face -----------------------------------------------------------
  std::vector<Tri> tris;
  std::vector<Index> tri_face;
  std::vector<Index> ring;
  for (Index f = 0; f < sub.num_faces(); ++f) {
    face_boundary_points(sub, f, ring);
    const Index c = sub.face_point(f);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      tris.push_back({c, ring[i], ring[(i + 1) % ring.size()]});
      tri_face.push_back(f);
    }
  }
  const std::size_t nt = tris.size();
  std::vector<double> face_prio(sub.num_faces());
  for (Index f = 0; f < sub.num_faces(); ++f) {
    double sum = 0;
    bool inf = false;
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    for (Index k = b; k < b + m; ++k) {
      const double e = sub.point_et[sub.corners[k]];
      if (std::isinf(e) && e > 0) inf = true;
      sum += e;
    }
    face_prio[f] = inf ? kInf : sum / m;
  }

  // ---- K: edges --------------------------------------------------------------------------------
  struct Rec {
    std::uint64_t key;
    Index tri;  // kNone for a loose edge
    int side;
  };
  std::vector<Rec> recs;
  recs.reserve(3 * nt + loose_edges.size());
  auto key_of = [](Index a, Index b) {
    return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
  };
  for (std::size_t t = 0; t < nt; ++t)
    for (int j = 0; j < 3; ++j)
      recs.push_back({key_of(tris[t][j], tris[t][(j + 1) % 3]), static_cast<Index>(t), j});
  for (const Segment& e : loose_edges) recs.push_back({key_of(e[0], e[1]), kNone, 0});
  for (const Segment& e : sub.curve_edges) recs.push_back({key_of(e[0], e[1]), kNone, 1});  // marks curve edges
  std::sort(recs.begin(), recs.end(), [](const Rec& a, const Rec& b) {
    return a.key < b.key || (a.key == b.key && a.tri < b.tri);
  });
  std::vector<Segment> edges;
  std::vector<char> edge_curve;
  std::vector<Index> edge_tri_begin{0}, edge_tris;
  std::vector<std::array<Index, 3>> tri_edge(nt);
  for (std::size_t i = 0; i < recs.size();) {
    std::size_t k = i;
    bool cell = false, curve = false;
    for (; k < recs.size() && recs[k].key == recs[i].key; ++k) {
      if (recs[k].tri != kNone || recs[k].side == 0) cell = true;
      else curve = true;
    }
    if (cell) {  // (a curve edge is always a fan spoke or a segment piece; never make one up)
      const Index e = static_cast<Index>(edges.size());
      edges.push_back({static_cast<Index>(recs[i].key >> 32), static_cast<Index>(recs[i].key & 0xffffffffu)});
      edge_curve.push_back(curve);
      for (std::size_t r = i; r < k; ++r)
        if (recs[r].tri != kNone) {
          tri_edge[recs[r].tri][recs[r].side] = e;
          edge_tris.push_back(recs[r].tri);
        }
      edge_tri_begin.push_back(static_cast<Index>(edge_tris.size()));
    }
    i = k;
  }
  recs.clear();
  recs.shrink_to_fit();
  const std::size_t ne = edges.size();

  // Vertex -> edges.
  std::vector<Index> vert_edge_begin(np + 1, 0), vert_edges(2 * ne);
  for (const Segment& e : edges) ++vert_edge_begin[e[0] + 1], ++vert_edge_begin[e[1] + 1];
  std::partial_sum(vert_edge_begin.begin(), vert_edge_begin.end(), vert_edge_begin.begin());
  {
    std::vector<Index> fill(vert_edge_begin.begin(), vert_edge_begin.end() - 1);
    for (std::size_t e = 0; e < ne; ++e)
      for (Index v : edges[e]) vert_edges[fill[v]++] = static_cast<Index>(e);
  }

  // Curve edge priorities.
  std::vector<double> edge_prio(ne, kNegInf);
  for (std::size_t e = 0; e < ne; ++e)
    if (edge_curve[e]) edge_prio[e] = mean_of(et_c[edges[e][0]], et_c[edges[e][1]]);

  Skeleton out;
  out.refined_faces = nt;
  out.refined_edges = ne;

  out.seconds_refine = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto t1 = Clock::now();
  // ---- protection ----------------------------------------------------------------------------
  std::vector<char> tri_protected(nt, 0);
  for (std::size_t t = 0; t < nt; ++t) tri_protected[t] = face_prio[tri_face[t]] > options.theta2;
  {
    UnionFind uf(nt);
    for (std::size_t e = 0; e < ne; ++e) {
      Index first = kNone;
      for (Index i = edge_tri_begin[e]; i < edge_tri_begin[e + 1]; ++i) {
        const Index t = edge_tris[i];
        if (!tri_protected[t]) continue;
        if (first == kNone) first = t;
        else uf.unite(first, t);
      }
    }
    std::vector<double> area(nt, 0.0);
    for (std::size_t t = 0; t < nt; ++t)
      if (tri_protected[t]) {
        const Vec3 &a = sub.point[tris[t][0]], &b = sub.point[tris[t][1]], &c = sub.point[tris[t][2]];
        area[uf.find(static_cast<Index>(t))] += 0.5 * (b - a).cross(c - a).norm();
      }
    std::vector<char> root_seen(nt, 0);
    for (std::size_t t = 0; t < nt; ++t)
      if (tri_protected[t]) {
        const Index r = uf.find(static_cast<Index>(t));
        if (area[r] < options.phi2) {
          if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_sheet_components;
          tri_protected[t] = 0;
        }
      }
  }
  std::vector<char> edge_protected(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) edge_protected[e] = edge_curve[e] && edge_prio[e] > options.theta1;
  {
    UnionFind uf(np);
    for (std::size_t e = 0; e < ne; ++e)
      if (edge_protected[e]) uf.unite(edges[e][0], edges[e][1]);
    std::vector<double> length(np, 0.0);
    for (std::size_t e = 0; e < ne; ++e)
      if (edge_protected[e])
        length[uf.find(edges[e][0])] += (sub.point[edges[e][0]] - sub.point[edges[e][1]]).norm();
    std::vector<char> root_seen(np, 0);
    for (std::size_t e = 0; e < ne; ++e)
      if (edge_protected[e]) {
        const Index r = uf.find(edges[e][0]);
        if (length[r] < options.phi1) {
          if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_curve_components;
          edge_protected[e] = 0;
        }
      }
  }
  std::vector<char> kept_tri(tri_protected), kept_edge(edge_protected), kept_vertex(np, 0);
  for (std::size_t t = 0; t < nt; ++t)
    if (kept_tri[t]) {
      ++out.protected_faces;
      for (Index e : tri_edge[t]) kept_edge[e] = 1;
    }
  for (std::size_t e = 0; e < ne; ++e) {
    out.protected_curve_edges += edge_protected[e];
    if (kept_edge[e]) kept_vertex[edges[e][0]] = kept_vertex[edges[e][1]] = 1;
  }

  // ---- contraction ---------------------------------------------------------------------------
  std::vector<char> tri_alive(nt, 1), edge_alive(ne, 1), vertex_alive(np, 0);
  for (Index v = 0; v < V; ++v) vertex_alive[v] = 1;
  for (const Segment& e : edges) vertex_alive[e[0]] = vertex_alive[e[1]] = 1;
  std::vector<Index> edge_count(ne), vertex_count(np);
  for (std::size_t e = 0; e < ne; ++e) edge_count[e] = edge_tri_begin[e + 1] - edge_tri_begin[e];
  for (std::size_t v = 0; v < np; ++v) vertex_count[v] = vert_edge_begin[v + 1] - vert_edge_begin[v];
  out.refined_vertices = static_cast<std::size_t>(std::count(vertex_alive.begin(), vertex_alive.end(), 1));

  std::priority_queue<Pair, std::vector<Pair>, PairLater> heap;
  auto try_edge_tri = [&](Index e) {
    if (!edge_alive[e] || edge_count[e] != 1 || kept_edge[e]) return;
    for (Index i = edge_tri_begin[e]; i < edge_tri_begin[e + 1]; ++i) {
      const Index t = edge_tris[i];
      if (!tri_alive[t]) continue;
      if (!kept_tri[t]) heap.push({edge_curve[e], face_prio[tri_face[t]], edge_prio[e], 0, e, t});
      return;
    }
  };
  auto try_vertex_edge = [&](Index v) {
    if (!vertex_alive[v] || vertex_count[v] != 1 || kept_vertex[v]) return;
    for (Index i = vert_edge_begin[v]; i < vert_edge_begin[v + 1]; ++i) {
      const Index e = vert_edges[i];
      if (!edge_alive[e]) continue;
      if (edge_count[e] == 0 && !kept_edge[e]) heap.push({edge_curve[e], edge_prio[e], kNegInf, 1, v, e});
      return;
    }
  };
  for (Index e = 0; e < ne; ++e) try_edge_tri(e);
  for (Index v = 0; v < np; ++v) try_vertex_edge(v);

  while (!heap.empty()) {
    const Pair p = heap.top();
    heap.pop();
    if (p.type == 0) {
      const Index e = p.sigma, t = p.tau;
      if (!tri_alive[t] || !edge_alive[e] || edge_count[e] != 1) continue;
      tri_alive[t] = 0;
      edge_alive[e] = 0;
      for (Index e2 : tri_edge[t]) --edge_count[e2];
      for (Index v : edges[e]) --vertex_count[v];
      for (Index e2 : tri_edge[t]) {
        if (e2 == e) continue;
        if (edge_count[e2] == 1) try_edge_tri(e2);
        else if (edge_count[e2] == 0) try_vertex_edge(edges[e2][0]), try_vertex_edge(edges[e2][1]);
      }
      for (Index v : edges[e]) try_vertex_edge(v);
    } else {
      const Index v = p.sigma, e = p.tau;
      if (!vertex_alive[v] || !edge_alive[e] || edge_count[e] != 0 || vertex_count[v] != 1) continue;
      vertex_alive[v] = 0;
      edge_alive[e] = 0;
      vertex_count[v] = 0;
      const Index w = edges[e][0] == v ? edges[e][1] : edges[e][0];
      --vertex_count[w];
      try_vertex_edge(w);
    }
  }

  out.seconds_contract = std::chrono::duration<double>(Clock::now() - t1).count();
  // ---- output --------------------------------------------------------------------------------
  std::vector<Index> local(np, kNone);
  for (std::size_t p = 0; p < np; ++p) {
    if (!vertex_alive[p]) continue;
    local[p] = static_cast<Index>(out.points.size());
    out.points.push_back(sub.point[p]);
    out.radius.push_back(sub.point_radius[p]);
    out.bt.push_back(sub.point_bt[p]);
    out.et.push_back(sub.point_et[p]);
    out.et_c.push_back(et_c[p]);
    out.kind.push_back(p < sub.num_nodes ? (g.is_vertex(static_cast<Index>(p)) ? 0 : 1)
                                         : p < sub.num_nodes + sub.num_segments ? 2 : 3);
  }
  for (std::size_t e = 0; e < ne; ++e)
    if (edge_alive[e]) {
      out.edges.push_back({local[edges[e][0]], local[edges[e][1]]});
      out.edge_curve.push_back(edge_curve[e]);
      out.edge_priority.push_back(edge_prio[e]);
    }
  for (std::size_t t = 0; t < nt; ++t)
    if (tri_alive[t]) {
      out.faces.push_back({local[tris[t][0]], local[tris[t][1]], local[tris[t][2]]});
      out.face_priority.push_back(face_prio[tri_face[t]]);
    }
  return out;
}

}  // namespace medax::et
