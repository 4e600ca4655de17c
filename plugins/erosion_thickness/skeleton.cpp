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
  int type;  // 0: (1-cell, 2-cell), 1: (0-cell, 1-cell)
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
  const Index N = sub.num_nodes, S = sub.num_segments, F = sub.num_faces();
  const std::vector<double> et_c = curve_erosion_thickness(sub);
  auto is_face_point = [&](Index p) { return p >= N + S; };
  auto key_of = [](Index a, Index b) {
    return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
  };
  Skeleton out;

  // ---- 1-cells ---------------------------------------------------------------------------------
  // Segment pieces (split at the dual point of a used segment), chords, spokes (the curve edges
  // from a face's dual point), loose edges. Ids in that order.
  std::vector<Segment> ends;
  std::vector<char> cell_curve;
  std::vector<Index> piece_base(S + 1);
  for (Index s = 0; s < S; ++s) {
    piece_base[s] = static_cast<Index>(ends.size());
    const auto nodes = sub.segment_nodes(g, s);
    if (sub.segment_used[s]) {
      ends.push_back({nodes[0], sub.segment_point(s)});
      ends.push_back({sub.segment_point(s), nodes[1]});
    } else {
      ends.push_back({nodes[0], nodes[1]});
    }
  }
  piece_base[S] = static_cast<Index>(ends.size());
  // Chords: endpoints from the faces' sides.
  const Index chord_base = static_cast<Index>(ends.size());
  ends.resize(ends.size() + sub.num_chords, Segment{kNone, kNone});
  for (Index f = 0; f < F; ++f) {
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    for (Index k = 0; k < m; ++k)
      if (sub.side_chord[b + k] != kNone)
        ends[chord_base + sub.side_chord[b + k]] = {sub.corners[b + k], sub.corners[b + (k + 1) % m]};
  }
  cell_curve.assign(ends.size(), 0);
  // Curve edges: spokes (face dual - point) become cells; segment dual - node edges mark pieces.
  std::vector<Index> spoke_begin(F + 1, 0);
  for (const Segment& e : sub.curve_edges) {
    const bool a = is_face_point(e[0]), bb = is_face_point(e[1]);
    if (a != bb) ++spoke_begin[(a ? e[0] : e[1]) - N - S + 1];
  }
  std::partial_sum(spoke_begin.begin(), spoke_begin.end(), spoke_begin.begin());
  std::vector<Index> spoke_target(spoke_begin[F]);
  {
    std::vector<Index> fill(spoke_begin.begin(), spoke_begin.end() - 1);
    for (const Segment& e : sub.curve_edges) {
      const bool a = is_face_point(e[0]), bb = is_face_point(e[1]);
      if (a != bb) spoke_target[fill[(a ? e[0] : e[1]) - N - S]++] = a ? e[1] : e[0];
      else if (!a) {  // segment dual - unburned node: the piece between them is a curve edge
        const Index sp = e[0] >= N ? e[0] : e[1], node = e[0] >= N ? e[1] : e[0];
        const Index s = sp - N;
        for (Index c = piece_base[s]; c < piece_base[s + 1]; ++c)
          if (ends[c][0] == node || ends[c][1] == node) cell_curve[c] = 1;
      }
    }
  }

  // ---- 2-cells: wedges ---------------------------------------------------------------------------
  // Face f's ring b_0..b_{m-1} (corners and used segment duals) is cut by its spokes into wedges;
  // a face with one spoke is one 2-cell whose boundary runs through the spoke twice.
  std::vector<Index> w_face, w_first, w_len;  // ring range [first, first + len] (cyclic), len >= 1
  std::vector<Index> w_bnd_begin{0}, w_bnd;   // boundary 1-cells, with multiplicity
  std::vector<Index> ring, ring_cell, cpos, spoke_cell;
  std::vector<Index> face_wedge_begin(F + 1, 0);
  std::vector<double> w_area;
  for (Index f = 0; f < F; ++f) {
    face_wedge_begin[f] = static_cast<Index>(w_face.size());
    face_boundary_points(sub, f, ring);
    const Index m = static_cast<Index>(ring.size());
    // The 1-cell between ring[i] and ring[i+1].
    ring_cell.clear();
    {
      const Index b = sub.face_begin[f], nc = sub.face_begin[f + 1] - b;
      for (Index k = 0; k < nc; ++k) {
        const Index s = sub.side_segment[b + k];
        if (s == kNone) {
          ring_cell.push_back(chord_base + sub.side_chord[b + k]);
          continue;
        }
        const Index corner = sub.corners[b + k];
        if (!sub.segment_used[s]) {
          ring_cell.push_back(piece_base[s]);
        } else {
          const bool from_first = ends[piece_base[s]][0] == corner;
          ring_cell.push_back(piece_base[s] + (from_first ? 0 : 1));
          ring_cell.push_back(piece_base[s] + (from_first ? 1 : 0));
        }
      }
    }
    // Spokes at ring positions.
    cpos.clear();
    spoke_cell.clear();
    for (Index i = 0; i < m; ++i)
      for (Index k = spoke_begin[f]; k < spoke_begin[f + 1]; ++k)
        if (spoke_target[k] == ring[i]) {
          cpos.push_back(i);
          spoke_cell.push_back(static_cast<Index>(ends.size()));
          ends.push_back({sub.face_point(f), ring[i]});
          cell_curve.push_back(1);
          break;
        }
    const Vec3& c = sub.point[sub.face_point(f)];
    auto wedge = [&](Index first, Index len, Index spoke_a, Index spoke_b) {
      w_face.push_back(f);
      w_first.push_back(first);
      w_len.push_back(len);
      double area = 0;
      if (spoke_a != kNone) w_bnd.push_back(spoke_a);
      for (Index i = 0; i < len; ++i) {
        const Index r = (first + i) % m;
        w_bnd.push_back(ring_cell[r]);
        area += 0.5 * (sub.point[ring[r]] - c).cross(sub.point[ring[(r + 1) % m]] - c).norm();
      }
      if (spoke_b != kNone) w_bnd.push_back(spoke_b);
      w_bnd_begin.push_back(static_cast<Index>(w_bnd.size()));
      w_area.push_back(area);
    };
    if (cpos.empty()) {
      wedge(0, m, kNone, kNone);
    } else {
      const std::size_t k = cpos.size();
      for (std::size_t j = 0; j < k; ++j) {
        const Index a = cpos[j], bpos = cpos[(j + 1) % k];
        const Index len = k == 1 ? m : (bpos + m - a) % m;
        wedge(a, len, spoke_cell[j], spoke_cell[(j + 1) % k]);
      }
    }
  }
  face_wedge_begin[F] = static_cast<Index>(w_face.size());
  const Index loose_base = static_cast<Index>(ends.size());
  for (const Segment& e : loose_edges) {
    ends.push_back(e);
    cell_curve.push_back(0);
  }
  const std::size_t ne = ends.size(), nw = w_face.size();

  // Priorities.
  std::vector<double> face_prio(F);
  for (Index f = 0; f < F; ++f) {
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
  std::vector<double> cell_prio(ne, kNegInf);
  for (std::size_t e = 0; e < ne; ++e)
    if (cell_curve[e]) cell_prio[e] = mean_of(et_c[ends[e][0]], et_c[ends[e][1]]);

  // Incidences: 1-cell -> wedges (with multiplicity), point -> 1-cells.
  std::vector<Index> cof_begin(ne + 1, 0), cof;
  for (Index c : w_bnd) ++cof_begin[c + 1];
  std::partial_sum(cof_begin.begin(), cof_begin.end(), cof_begin.begin());
  cof.resize(cof_begin[ne]);
  {
    std::vector<Index> fill(cof_begin.begin(), cof_begin.end() - 1);
    for (Index w = 0; w < nw; ++w)
      for (Index i = w_bnd_begin[w]; i < w_bnd_begin[w + 1]; ++i) cof[fill[w_bnd[i]]++] = w;
  }
  std::vector<Index> inc_begin(np + 1, 0), inc(2 * ne);
  for (const Segment& e : ends) ++inc_begin[e[0] + 1], ++inc_begin[e[1] + 1];
  std::partial_sum(inc_begin.begin(), inc_begin.end(), inc_begin.begin());
  {
    std::vector<Index> fill(inc_begin.begin(), inc_begin.end() - 1);
    for (std::size_t e = 0; e < ne; ++e)
      for (Index v : ends[e]) inc[fill[v]++] = static_cast<Index>(e);
  }
  out.refined_faces = nw;
  out.refined_edges = ne;
  out.seconds_refine = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto t1 = Clock::now();

  // ---- protection ----------------------------------------------------------------------------
  std::vector<char> w_protected(nw, 0);
  for (std::size_t w = 0; w < nw; ++w) w_protected[w] = face_prio[w_face[w]] > options.theta2;
  {
    UnionFind uf(nw);
    for (std::size_t e = 0; e < ne; ++e) {
      Index first = kNone;
      for (Index i = cof_begin[e]; i < cof_begin[e + 1]; ++i) {
        const Index w = cof[i];
        if (!w_protected[w]) continue;
        if (first == kNone) first = w;
        else uf.unite(first, w);
      }
    }
    std::vector<double> area(nw, 0.0);
    for (std::size_t w = 0; w < nw; ++w)
      if (w_protected[w]) area[uf.find(static_cast<Index>(w))] += w_area[w];
    std::vector<char> root_seen(nw, 0);
    for (std::size_t w = 0; w < nw; ++w)
      if (w_protected[w]) {
        const Index r = uf.find(static_cast<Index>(w));
        if (area[r] < options.phi2) {
          if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_sheet_components;
          w_protected[w] = 0;
        }
      }
  }
  std::vector<char> e_protected(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) e_protected[e] = cell_curve[e] && cell_prio[e] > options.theta1;
  {
    UnionFind uf(np);
    for (std::size_t e = 0; e < ne; ++e)
      if (e_protected[e]) uf.unite(ends[e][0], ends[e][1]);
    std::vector<double> length(np, 0.0);
    for (std::size_t e = 0; e < ne; ++e)
      if (e_protected[e]) length[uf.find(ends[e][0])] += (sub.point[ends[e][0]] - sub.point[ends[e][1]]).norm();
    std::vector<char> root_seen(np, 0);
    for (std::size_t e = 0; e < ne; ++e)
      if (e_protected[e]) {
        const Index r = uf.find(ends[e][0]);
        if (length[r] < options.phi1) {
          if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_curve_components;
          e_protected[e] = 0;
        }
      }
  }
  std::vector<char> kept_w(w_protected), kept_e(e_protected), kept_v(np, 0);
  for (std::size_t w = 0; w < nw; ++w)
    if (kept_w[w]) {
      ++out.protected_faces;
      out.protected_area += w_area[w];
      for (Index i = w_bnd_begin[w]; i < w_bnd_begin[w + 1]; ++i) kept_e[w_bnd[i]] = 1;
    }
  for (std::size_t e = 0; e < ne; ++e) {
    out.protected_curve_edges += e_protected[e];
    if (kept_e[e]) kept_v[ends[e][0]] = kept_v[ends[e][1]] = 1;
  }
  out.seconds_protect = std::chrono::duration<double>(Clock::now() - t1).count();

  // ---- contraction ---------------------------------------------------------------------------
  std::vector<char> w_alive(nw, 1), e_alive(ne, 1), v_alive(np, 0);
  for (Index v = 0; v < V; ++v) v_alive[v] = 1;
  for (const Segment& e : ends) v_alive[e[0]] = v_alive[e[1]] = 1;
  out.refined_vertices = static_cast<std::size_t>(std::count(v_alive.begin(), v_alive.end(), 1));
  std::vector<Index> e_count(ne), v_count(np);
  for (std::size_t e = 0; e < ne; ++e) e_count[e] = cof_begin[e + 1] - cof_begin[e];
  for (std::size_t v = 0; v < np; ++v) v_count[v] = inc_begin[v + 1] - inc_begin[v];

  // Three queues, popped in this order, give the order (phase, prio tau, prio sigma, type, tau,
  // sigma) with small entries: phase-0 (0-cell, 1-cell) pairs (prio tau = -inf) keyed by
  // (1-cell, 0-cell); phase-0 (1-cell, wedge) pairs (prio sigma = -inf) keyed by (rank of the
  // wedge by (prio, id), 1-cell); phase-1 pairs with their full key.
  std::vector<Index> wedge_rank(nw);
  {
    std::vector<Index> faces(F);
    std::iota(faces.begin(), faces.end(), Index(0));
    std::sort(faces.begin(), faces.end(), [&](Index a, Index b) {
      return face_prio[a] < face_prio[b] || (face_prio[a] == face_prio[b] && a < b);
    });
    Index r = 0;
    for (Index f : faces)
      for (Index w = face_wedge_begin[f]; w < face_wedge_begin[f + 1]; ++w) wedge_rank[w] = r++;
  }
  using Key = std::uint64_t;
  std::priority_queue<Key, std::vector<Key>, std::greater<>> vertex_pairs, wedge_pairs;
  std::priority_queue<Pair, std::vector<Pair>, PairLater> curve_pairs;
  // Phase-1 pairs are only queued once phase 0 has run dry (then every free one is found by a
  // scan): queued earlier, most would be stale by then and only slow the queue down.
  bool curves_active = false;
  auto try_edge_wedge = [&](Index e) {
    if (!e_alive[e] || e_count[e] != 1 || kept_e[e]) return;
    for (Index i = cof_begin[e]; i < cof_begin[e + 1]; ++i) {
      const Index w = cof[i];
      if (!w_alive[w]) continue;
      if (kept_w[w]) return;
      if (!cell_curve[e]) wedge_pairs.push((Key(wedge_rank[w]) << 32) | e);
      else if (curves_active) curve_pairs.push({1, face_prio[w_face[w]], cell_prio[e], 0, e, w});
      return;
    }
  };
  auto try_vertex_edge = [&](Index v) {
    if (!v_alive[v] || v_count[v] != 1 || kept_v[v]) return;
    for (Index i = inc_begin[v]; i < inc_begin[v + 1]; ++i) {
      const Index e = inc[i];
      if (!e_alive[e]) continue;
      if (e_count[e] != 0 || kept_e[e]) return;
      if (!cell_curve[e]) vertex_pairs.push((Key(e) << 32) | v);
      else if (curves_active) curve_pairs.push({1, cell_prio[e], kNegInf, 1, v, e});
      return;
    }
  };
  for (Index e = 0; e < ne; ++e) try_edge_wedge(e);
  for (Index v = 0; v < np; ++v) try_vertex_edge(v);
  auto collapse_wedge = [&](Index e, Index w) {
    if (!w_alive[w] || !e_alive[e] || e_count[e] != 1) return;
    w_alive[w] = 0;
    e_alive[e] = 0;
    for (Index i = w_bnd_begin[w]; i < w_bnd_begin[w + 1]; ++i) --e_count[w_bnd[i]];
    for (Index v : ends[e]) --v_count[v];
    for (Index i = w_bnd_begin[w]; i < w_bnd_begin[w + 1]; ++i) {
      const Index e2 = w_bnd[i];
      if (e2 == e || !e_alive[e2]) continue;
      if (e_count[e2] == 1) try_edge_wedge(e2);
      else if (e_count[e2] == 0) try_vertex_edge(ends[e2][0]), try_vertex_edge(ends[e2][1]);
    }
    for (Index v : ends[e]) try_vertex_edge(v);
  };
  auto collapse_vertex = [&](Index v, Index e) {
    if (!v_alive[v] || !e_alive[e] || e_count[e] != 0 || v_count[v] != 1) return;
    v_alive[v] = 0;
    e_alive[e] = 0;
    v_count[v] = 0;
    const Index w = ends[e][0] == v ? ends[e][1] : ends[e][0];
    --v_count[w];
    try_vertex_edge(w);
  };
  std::vector<Index> wedge_of_rank(nw);
  for (Index w = 0; w < nw; ++w) wedge_of_rank[wedge_rank[w]] = w;
  for (;;) {
    if (!vertex_pairs.empty()) {
      const Key k = vertex_pairs.top();
      vertex_pairs.pop();
      collapse_vertex(static_cast<Index>(k & 0xffffffffu), static_cast<Index>(k >> 32));
    } else if (!wedge_pairs.empty()) {
      const Key k = wedge_pairs.top();
      wedge_pairs.pop();
      collapse_wedge(static_cast<Index>(k & 0xffffffffu), wedge_of_rank[k >> 32]);
    } else if (!curves_active) {
      curves_active = true;
      for (Index e = 0; e < ne; ++e)
        if (cell_curve[e]) try_edge_wedge(e), try_vertex_edge(ends[e][0]), try_vertex_edge(ends[e][1]);
    } else if (!curve_pairs.empty()) {
      const Pair p = curve_pairs.top();
      curve_pairs.pop();
      if (p.type == 0) collapse_wedge(p.sigma, p.tau);
      else collapse_vertex(p.sigma, p.tau);
    } else {
      break;
    }
  }
  out.seconds_contract = std::chrono::duration<double>(Clock::now() - t1).count();
  const auto t2 = Clock::now();

  // ---- output --------------------------------------------------------------------------------
  // Coarsening: a triangle of the input whose wedges all survive is written as itself (or as a
  // fan from its centre over the points its sides must keep), and a point on an edge whose
  // triangles all survive whole is dropped: the same disk, the same topology, far fewer
  // triangles. The other surviving wedges are written as fans from their face's dual point.
  const TriangleComplex& cx = *g.cx;
  const std::size_t nmt = cx.num_triangles();
  std::vector<char> whole(nmt, 0);
  if (options.coarsen)
    for (std::size_t T = 0; T < nmt; ++T) {
      bool all = true;
      for (Index f = sub.tri_face_begin[T]; f < sub.tri_face_begin[T + 1] && all; ++f)
        for (Index w = face_wedge_begin[f]; w < face_wedge_begin[f + 1] && all; ++w) all = w_alive[w];
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
    out.kind.push_back(p < N ? (g.is_vertex(static_cast<Index>(p)) ? 0 : 1) : p < N + S ? 2 : 3);
    return local[p];
  };
  // Vertices left without edges (isolated input vertices, the point a component collapsed to).
  for (Index p = 0; p < np; ++p)
    if (v_alive[p] && v_count[p] == 0) point(p);
  for (std::size_t T = 0; T < nmt; ++T) {
    if (!whole[T]) {
      for (Index f = sub.tri_face_begin[T]; f < sub.tri_face_begin[T + 1]; ++f) {
        bool any = false;
        for (Index w = face_wedge_begin[f]; w < face_wedge_begin[f + 1] && !any; ++w) any = w_alive[w];
        if (!any) continue;
        face_boundary_points(sub, f, ring);
        const Index m = static_cast<Index>(ring.size()), c = point(sub.face_point(f));
        for (Index w = face_wedge_begin[f]; w < face_wedge_begin[f + 1]; ++w) {
          if (!w_alive[w]) continue;
          for (Index i = 0; i < w_len[w]; ++i) {
            const Index r = (w_first[w] + i) % m;
            out.faces.push_back({c, point(ring[r]), point(ring[(r + 1) % m])});
            out.face_priority.push_back(face_prio[f]);
          }
        }
      }
      continue;
    }
    // Area-weighted priority of the whole triangle.
    double area = 0, weighted = 0;
    bool inf = false;
    for (Index f = sub.tri_face_begin[T]; f < sub.tri_face_begin[T + 1]; ++f)
      for (Index w = face_wedge_begin[f]; w < face_wedge_begin[f + 1]; ++w) {
        if (std::isinf(face_prio[f])) inf = true;
        else area += w_area[w], weighted += w_area[w] * face_prio[f];
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
    ++out.coarse_triangles;
    if (ring.size() == 3) {
      out.faces.push_back({point(ring[0]), point(ring[1]), point(ring[2])});
      out.face_priority.push_back(prio);
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
  }
  // Edges: the sides of the written triangles and the surviving 1-cells that bound nothing.
  struct EdgeOut {
    std::uint64_t key;
    char curve;
    double prio;
  };
  std::vector<EdgeOut> eo;
  for (const Tri& t : out.faces)
    for (int j = 0; j < 3; ++j) eo.push_back({key_of(t[j], t[(j + 1) % 3]), 0, kNegInf});
  std::vector<EdgeOut> curve_sides;  // surviving curve cells, to label the sides that are curve edges
  for (std::size_t e = 0; e < ne; ++e) {
    if (!e_alive[e]) continue;
    if (e_count[e] == 0) {
      eo.push_back({key_of(point(ends[e][0]), point(ends[e][1])), cell_curve[e], cell_prio[e]});
    } else if (cell_curve[e] && local[ends[e][0]] != kNone && local[ends[e][1]] != kNone) {
      curve_sides.push_back({key_of(local[ends[e][0]], local[ends[e][1]]), 1, cell_prio[e]});
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
  (void)loose_base;
  out.seconds_output = std::chrono::duration<double>(Clock::now() - t2).count();
  return out;
}

}  // namespace medax::et
