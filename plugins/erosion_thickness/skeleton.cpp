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

  const double t_fans = std::chrono::duration<double>(Clock::now() - t0).count();
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
  out.seconds_fans = t_fans;
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

  const double t_protect = std::chrono::duration<double>(Clock::now() - t1).count();
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
  out.seconds_protect = t_protect;
  const auto t2 = Clock::now();
  // ---- output --------------------------------------------------------------------------------
  // Coarsening: a triangle of the input whose fan triangles all survive is written as itself
  // (or as a fan from its centre over the points its sides must keep), and a point on an edge
  // whose triangles all survive whole is dropped: the same disk, the same topology, far fewer
  // triangles. Everything else is written as the refined cells that survived.
  const TriangleComplex& cx = *g.cx;
  const std::size_t nmt = cx.num_triangles();
  std::vector<Index> face_first_tri(sub.num_faces() + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) ++face_first_tri[tri_face[t] + 1];
  std::partial_sum(face_first_tri.begin(), face_first_tri.end(), face_first_tri.begin());
  std::vector<char> whole(nmt, 0);
  if (options.coarsen)
    for (std::size_t T = 0; T < nmt; ++T) {
      bool all = true;
      for (Index f = sub.tri_face_begin[T]; f < sub.tri_face_begin[T + 1] && all; ++f)
        for (Index k = face_first_tri[f]; k < face_first_tri[f + 1] && all; ++k) all = tri_alive[k];
      whole[T] = all;
    }
  std::vector<char> coarse_edge(cx.num_edges(), 0);
  for (std::size_t e = 0; e < cx.num_edges(); ++e) {
    bool all = true;
    for (Index i = cx.edge_tri_begin[e]; i < cx.edge_tri_begin[e + 1] && all; ++i) all = whole[cx.edge_tris[i]];
    coarse_edge[e] = all;
  }

  std::vector<Index> local(np, kNone);
  auto point = [&](Index p) {
    if (local[p] != kNone) return local[p];
    local[p] = static_cast<Index>(out.points.size());
    out.points.push_back(sub.point[p]);
    out.radius.push_back(sub.point_radius[p]);
    out.bt.push_back(sub.point_bt[p]);
    out.et.push_back(sub.point_et[p]);
    out.et_c.push_back(et_c[p]);
    out.kind.push_back(p < sub.num_nodes ? (g.is_vertex(static_cast<Index>(p)) ? 0 : 1)
                                         : p < sub.num_nodes + sub.num_segments ? 2 : 3);
    return local[p];
  };
  // Vertices left without edges (isolated input vertices, the point a component collapsed to).
  for (Index p = 0; p < np; ++p)
    if (vertex_alive[p] && vertex_count[p] == 0) point(p);
  ring.clear();
  for (std::size_t T = 0; T < nmt; ++T) {
    if (!whole[T]) {
      for (Index f = sub.tri_face_begin[T]; f < sub.tri_face_begin[T + 1]; ++f)
        for (Index k = face_first_tri[f]; k < face_first_tri[f + 1]; ++k)
          if (tri_alive[k]) {
            out.faces.push_back({point(tris[k][0]), point(tris[k][1]), point(tris[k][2])});
            out.face_priority.push_back(face_prio[f]);
          }
      continue;
    }
    // Area-weighted priority of the whole triangle.
    double area = 0, weighted = 0;
    bool inf = false;
    for (Index f = sub.tri_face_begin[T]; f < sub.tri_face_begin[T + 1]; ++f)
      for (Index k = face_first_tri[f]; k < face_first_tri[f + 1]; ++k) {
        const Vec3 &a = sub.point[tris[k][0]], &b = sub.point[tris[k][1]], &c = sub.point[tris[k][2]];
        const double A = 0.5 * (b - a).cross(c - a).norm();
        if (std::isinf(face_prio[f])) inf = true;
        else area += A, weighted += A * face_prio[f];
      }
    const double prio = inf ? kInf : area > 0 ? weighted / area : face_prio[sub.tri_face_begin[T]];
    ring.clear();
    for (int j = 0; j < 3; ++j) {
      ring.push_back(cx.triangles[T][j]);
      const Index e = cx.tri_edges[T][j];
      if (coarse_edge[e]) continue;
      const Index n = g.samples_on(e);
      const bool fwd = cx.side_forward(static_cast<Index>(T), j);
      for (Index k = 0; k <= n; ++k) {
        if (k > 0) ring.push_back(g.side_node(static_cast<Index>(T), j, k));
        const Index s = sub.segment_begin[e] + (fwd ? k : n - k);
        if (sub.segment_used[s]) ring.push_back(sub.segment_point(s));
      }
    }
    if (ring.size() == 3) {
      out.faces.push_back({point(ring[0]), point(ring[1]), point(ring[2])});
      out.face_priority.push_back(prio);
      ++out.coarse_triangles;
      continue;
    }
    // Fan from the triangle's centre (attributes: the mean of its corners').
    const Index centre = static_cast<Index>(out.points.size());
    Vec3 c = Vec3::Zero();
    double r = 0, b = 0;
    for (Index v : cx.triangles[T]) c += sub.point[v], r += sub.point_radius[v], b += sub.point_bt[v];
    out.points.push_back(c / 3);
    out.radius.push_back(r / 3);
    out.bt.push_back(b / 3);
    out.et.push_back(std::isinf(b) ? kInf : (b - r) / 3);
    out.et_c.push_back(std::numeric_limits<double>::quiet_NaN());
    out.kind.push_back(4);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      out.faces.push_back({centre, point(ring[i]), point(ring[(i + 1) % ring.size()])});
      out.face_priority.push_back(prio);
    }
    ++out.coarse_triangles;
  }
  // Edges: the sides of the written triangles and the surviving edges that bound no triangle.
  struct EdgeOut {
    std::uint64_t key;
    char curve;
    double prio;
  };
  std::vector<EdgeOut> eo;
  for (const Tri& t : out.faces)
    for (int j = 0; j < 3; ++j) eo.push_back({key_of(t[j], t[(j + 1) % 3]), 0, kNegInf});
  std::vector<EdgeOut> curve_sides;  // surviving curve edges, to label the sides that are curve edges
  for (std::size_t e = 0; e < ne; ++e) {
    if (!edge_alive[e]) continue;
    if (edge_count[e] == 0) {
      eo.push_back({key_of(point(edges[e][0]), point(edges[e][1])), edge_curve[e], edge_prio[e]});
    } else if (edge_curve[e] && local[edges[e][0]] != kNone && local[edges[e][1]] != kNone) {
      curve_sides.push_back({key_of(local[edges[e][0]], local[edges[e][1]]), 1, edge_prio[e]});
    }
  }
  auto by_key = [](const EdgeOut& a, const EdgeOut& b) { return a.key < b.key; };
  std::sort(curve_sides.begin(), curve_sides.end(), by_key);
  std::sort(eo.begin(), eo.end(), [](const EdgeOut& a, const EdgeOut& b) {
    return a.key < b.key || (a.key == b.key && a.curve > b.curve);
  });
  for (std::size_t i = 0; i < eo.size(); ++i) {
    if (i > 0 && eo[i].key == eo[i - 1].key) continue;
    EdgeOut e = eo[i];
    if (!e.curve) {
      const auto it = std::lower_bound(curve_sides.begin(), curve_sides.end(), e, by_key);
      if (it != curve_sides.end() && it->key == e.key) e = *it;
    }
    out.edges.push_back({static_cast<Index>(e.key >> 32), static_cast<Index>(e.key & 0xffffffffu)});
    out.edge_curve.push_back(e.curve);
    out.edge_priority.push_back(e.prio);
  }
  out.seconds_output = std::chrono::duration<double>(Clock::now() - t2).count();
  return out;
}

}  // namespace medax::et
