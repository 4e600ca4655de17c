#include "skeleton.hpp"

#include <medax/union_find.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

namespace medax::et {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double mean_of(double a, double b) {
  if (std::isinf(a) && a > 0) return a;
  if (std::isinf(b) && b > 0) return b;
  return 0.5 * (a + b);
}

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

// ---- 1-cells -------------------------------------------------------------------------------------

/// Segment pieces (split at the dual point of a used segment) and chords, with their endpoints.
void add_pieces_and_chords(const BurnGraph& g, const Subdivision& sub, CellComplex& k) {
  const Index S = sub.num_segments, F = sub.num_faces();
  k.piece_base.resize(S + 1);
  for (Index s = 0; s < S; ++s) {
    k.piece_base[s] = static_cast<Index>(k.ends.size());
    const auto nodes = sub.segment_nodes(g, s);
    if (sub.segment_used[s]) {
      k.ends.push_back({nodes[0], sub.segment_point(s)});
      k.ends.push_back({sub.segment_point(s), nodes[1]});
    } else {
      k.ends.push_back({nodes[0], nodes[1]});
    }
  }
  k.piece_base[S] = static_cast<Index>(k.ends.size());
  // Chords: endpoints from the faces' sides.
  k.chord_base = static_cast<Index>(k.ends.size());
  k.ends.resize(k.ends.size() + sub.num_chords, Segment{kNone, kNone});
  for (Index f = 0; f < F; ++f) {
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    for (Index j = 0; j < m; ++j)
      if (sub.side_chord[b + j] != kNone)
        k.ends[k.chord_base + sub.side_chord[b + j]] = {sub.corners[b + j], sub.corners[b + (j + 1) % m]};
  }
  k.curve.assign(k.ends.size(), 0);
}

/// The curve edges: the spokes (face dual - point) per face, to become cells with the wedges;
/// a segment dual - unburned node edge marks the piece between them as a curve cell.
void add_spoke_targets(const Subdivision& sub, CellComplex& k) {
  const Index N = sub.num_nodes, S = sub.num_segments, F = sub.num_faces();
  auto is_face_point = [&](Index p) { return p >= N + S; };
  k.spoke_begin.assign(F + 1, 0);
  for (const Segment& e : sub.curve_edges) {
    const bool a = is_face_point(e[0]), b = is_face_point(e[1]);
    if (a != b) ++k.spoke_begin[(a ? e[0] : e[1]) - N - S + 1];
  }
  std::partial_sum(k.spoke_begin.begin(), k.spoke_begin.end(), k.spoke_begin.begin());
  k.spoke_target.resize(k.spoke_begin[F]);
  std::vector<Index> fill(k.spoke_begin.begin(), k.spoke_begin.end() - 1);
  for (const Segment& e : sub.curve_edges) {
    const bool a = is_face_point(e[0]), b = is_face_point(e[1]);
    if (a != b) {
      k.spoke_target[fill[(a ? e[0] : e[1]) - N - S]++] = a ? e[1] : e[0];
    } else if (!a) {  // segment dual - unburned node: the piece between them is a curve edge
      const Index sp = e[0] >= N ? e[0] : e[1], node = e[0] >= N ? e[1] : e[0];
      const Index s = sp - N;
      for (Index c = k.piece_base[s]; c < k.piece_base[s + 1]; ++c)
        if (k.ends[c][0] == node || k.ends[c][1] == node) k.curve[c] = 1;
    }
  }
}

// ---- 2-cells: wedges -----------------------------------------------------------------------------

/// The 1-cell between ring[i] and ring[i+1] of face f, for every i of its ring.
void ring_cells(const Subdivision& sub, const CellComplex& k, Index f, std::vector<Index>& out) {
  out.clear();
  const Index b = sub.face_begin[f], nc = sub.face_begin[f + 1] - b;
  for (Index j = 0; j < nc; ++j) {
    const Index s = sub.side_segment[b + j];
    if (s == kNone) {
      out.push_back(k.chord_base + sub.side_chord[b + j]);
      continue;
    }
    const Index corner = sub.corners[b + j];
    if (!sub.segment_used[s]) {
      out.push_back(k.piece_base[s]);
    } else {
      const bool from_first = k.ends[k.piece_base[s]][0] == corner;
      out.push_back(k.piece_base[s] + (from_first ? 0 : 1));
      out.push_back(k.piece_base[s] + (from_first ? 1 : 0));
    }
  }
}

/// Adds a spoke 1-cell for each spoke of face f, in ring order: `pos` gets their ring positions,
/// `cells` their ids.
void add_face_spokes(const Subdivision& sub, Index f, const std::vector<Index>& ring, CellComplex& k,
                     std::vector<Index>& pos, std::vector<Index>& cells) {
  pos.clear();
  cells.clear();
  const Index m = static_cast<Index>(ring.size());
  for (Index i = 0; i < m; ++i)
    for (Index j = k.spoke_begin[f]; j < k.spoke_begin[f + 1]; ++j)
      if (k.spoke_target[j] == ring[i]) {
        pos.push_back(i);
        cells.push_back(static_cast<Index>(k.ends.size()));
        k.ends.push_back({sub.face_point(f), ring[i]});
        k.curve.push_back(1);
        break;
      }
}

/// Adds the wedge of face f over ring positions first .. first + len (cyclic), bounded by spokes
/// a and b (kNone: none).
void add_wedge(const Subdivision& sub, Index f, const std::vector<Index>& ring, const std::vector<Index>& ring_cell,
               Index first, Index len, Index spoke_a, Index spoke_b, CellComplex& k) {
  const Index m = static_cast<Index>(ring.size());
  const Vec3& c = sub.point[sub.face_point(f)];
  k.w_face.push_back(f);
  k.w_first.push_back(first);
  k.w_len.push_back(len);
  double area = 0;
  if (spoke_a != kNone) k.w_bnd.push_back(spoke_a);
  for (Index i = 0; i < len; ++i) {
    const Index r = (first + i) % m;
    k.w_bnd.push_back(ring_cell[r]);
    area += 0.5 * (sub.point[ring[r]] - c).cross(sub.point[ring[(r + 1) % m]] - c).norm();
  }
  if (spoke_b != kNone) k.w_bnd.push_back(spoke_b);
  k.w_bnd_begin.push_back(static_cast<Index>(k.w_bnd.size()));
  k.w_area.push_back(area);
}

/// Face f's ring b_0..b_{m-1} (corners and used segment duals) is cut by its spokes into wedges;
/// a face with one spoke is one 2-cell whose boundary runs through the spoke twice.
void add_wedges(const Subdivision& sub, CellComplex& k) {
  const Index F = sub.num_faces();
  k.face_wedge_begin.assign(F + 1, 0);
  std::vector<Index> ring, ring_cell, cpos, spoke_cell;
  for (Index f = 0; f < F; ++f) {
    k.face_wedge_begin[f] = static_cast<Index>(k.w_face.size());
    face_boundary_points(sub, f, ring);
    ring_cells(sub, k, f, ring_cell);
    add_face_spokes(sub, f, ring, k, cpos, spoke_cell);
    const Index m = static_cast<Index>(ring.size());
    if (cpos.empty()) {
      add_wedge(sub, f, ring, ring_cell, 0, m, kNone, kNone, k);
      continue;
    }
    const std::size_t n = cpos.size();
    for (std::size_t j = 0; j < n; ++j) {
      const Index a = cpos[j], b = cpos[(j + 1) % n];
      const Index len = n == 1 ? m : (b + m - a) % m;
      add_wedge(sub, f, ring, ring_cell, a, len, spoke_cell[j], spoke_cell[(j + 1) % n], k);
    }
  }
  k.face_wedge_begin[F] = static_cast<Index>(k.w_face.size());
}

// ---- priorities and incidences -------------------------------------------------------------------

void compute_priorities(const Subdivision& sub, const std::vector<double>& et_c, CellComplex& k) {
  const Index F = sub.num_faces();
  k.face_prio.resize(F);
  for (Index f = 0; f < F; ++f) {
    double sum = 0;
    bool inf = false;
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    for (Index j = b; j < b + m; ++j) {
      const double e = sub.point_et[sub.corners[j]];
      if (std::isinf(e) && e > 0) inf = true;
      sum += e;
    }
    k.face_prio[f] = inf ? kInf : sum / m;
  }
  const std::size_t ne = k.num_cells();
  k.cell_prio.assign(ne, kNegInf);
  for (std::size_t e = 0; e < ne; ++e)
    if (k.curve[e]) k.cell_prio[e] = mean_of(et_c[k.ends[e][0]], et_c[k.ends[e][1]]);
}

/// 1-cell -> wedges (with multiplicity), point -> 1-cells.
void build_incidences(std::size_t np, CellComplex& k) {
  const std::size_t ne = k.num_cells(), nw = k.num_wedges();
  k.cof_begin.assign(ne + 1, 0);
  for (Index c : k.w_bnd) ++k.cof_begin[c + 1];
  std::partial_sum(k.cof_begin.begin(), k.cof_begin.end(), k.cof_begin.begin());
  k.cof.resize(k.cof_begin[ne]);
  std::vector<Index> fill(k.cof_begin.begin(), k.cof_begin.end() - 1);
  for (Index w = 0; w < nw; ++w)
    for (Index i = k.w_bnd_begin[w]; i < k.w_bnd_begin[w + 1]; ++i) k.cof[fill[k.w_bnd[i]]++] = w;
  k.inc_begin.assign(np + 1, 0);
  k.inc.resize(2 * ne);
  for (const Segment& e : k.ends) ++k.inc_begin[e[0] + 1], ++k.inc_begin[e[1] + 1];
  std::partial_sum(k.inc_begin.begin(), k.inc_begin.end(), k.inc_begin.begin());
  fill.assign(k.inc_begin.begin(), k.inc_begin.end() - 1);
  for (std::size_t e = 0; e < ne; ++e)
    for (Index v : k.ends[e]) k.inc[fill[v]++] = static_cast<Index>(e);
}

CellComplex build_cell_complex(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                               const std::vector<double>& et_c) {
  CellComplex k;
  add_pieces_and_chords(g, sub, k);
  add_spoke_targets(sub, k);
  add_wedges(sub, k);
  for (const Segment& e : loose_edges) {
    k.ends.push_back(e);
    k.curve.push_back(0);
  }
  compute_priorities(sub, et_c, k);
  build_incidences(sub.num_points(), k);
  return k;
}

// ---- protection ----------------------------------------------------------------------------------

/// Wedges with priority > theta2, minus the components (wedges sharing a 1-cell) of area < phi2.
std::vector<char> protect_sheets(const CellComplex& k, const SkeletonOptions& options, Skeleton& out) {
  const std::size_t ne = k.num_cells(), nw = k.num_wedges();
  std::vector<char> prot(nw, 0);
  for (std::size_t w = 0; w < nw; ++w) prot[w] = k.face_prio[k.w_face[w]] > options.theta2;
  UnionFind uf(nw);
  for (std::size_t e = 0; e < ne; ++e) {
    Index first = kNone;
    for (Index i = k.cof_begin[e]; i < k.cof_begin[e + 1]; ++i) {
      const Index w = k.cof[i];
      if (!prot[w]) continue;
      if (first == kNone) first = w;
      else uf.unite(first, w);
    }
  }
  std::vector<double> area(nw, 0.0);
  for (std::size_t w = 0; w < nw; ++w)
    if (prot[w]) area[uf.find(static_cast<Index>(w))] += k.w_area[w];
  std::vector<char> root_seen(nw, 0);
  for (std::size_t w = 0; w < nw; ++w)
    if (prot[w]) {
      const Index r = uf.find(static_cast<Index>(w));
      if (area[r] < options.phi2) {
        if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_sheet_components;
        prot[w] = 0;
      }
    }
  return prot;
}

/// Curve 1-cells with priority > theta1, minus the components (sharing a point) of length < phi1.
std::vector<char> protect_curves(const Subdivision& sub, const CellComplex& k, const SkeletonOptions& options,
                                 Skeleton& out) {
  const std::size_t ne = k.num_cells(), np = sub.num_points();
  std::vector<char> prot(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) prot[e] = k.curve[e] && k.cell_prio[e] > options.theta1;
  UnionFind uf(np);
  for (std::size_t e = 0; e < ne; ++e)
    if (prot[e]) uf.unite(k.ends[e][0], k.ends[e][1]);
  std::vector<double> length(np, 0.0);
  for (std::size_t e = 0; e < ne; ++e)
    if (prot[e]) length[uf.find(k.ends[e][0])] += (sub.point[k.ends[e][0]] - sub.point[k.ends[e][1]]).norm();
  std::vector<char> root_seen(np, 0);
  for (std::size_t e = 0; e < ne; ++e)
    if (prot[e]) {
      const Index r = uf.find(k.ends[e][0]);
      if (length[r] < options.phi1) {
        if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_curve_components;
        prot[e] = 0;
      }
    }
  return prot;
}

/// The closure of the protected cells: what the contraction must keep.
struct Kept {
  std::vector<char> w, e, v;
};

Kept protect(const Subdivision& sub, const CellComplex& k, const SkeletonOptions& options, Skeleton& out) {
  Kept kept;
  kept.w = protect_sheets(k, options, out);
  const std::vector<char> e_protected = protect_curves(sub, k, options, out);
  kept.e = e_protected;
  kept.v.assign(sub.num_points(), 0);
  for (std::size_t w = 0; w < k.num_wedges(); ++w)
    if (kept.w[w]) {
      ++out.protected_faces;
      out.protected_area += k.w_area[w];
      for (Index i = k.w_bnd_begin[w]; i < k.w_bnd_begin[w + 1]; ++i) kept.e[k.w_bnd[i]] = 1;
    }
  for (std::size_t e = 0; e < k.num_cells(); ++e) {
    out.protected_curve_edges += e_protected[e];
    if (kept.e[e]) kept.v[k.ends[e][0]] = kept.v[k.ends[e][1]] = 1;
  }
  return kept;
}

// ---- contraction ---------------------------------------------------------------------------------

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

/// Removes free pairs (sigma, tau) outside the kept cells until none is left (Liu et al. 2010).
/// Three queues, popped in this order, give the order (phase, prio tau, prio sigma, type, tau,
/// sigma) with small entries: phase-0 (0-cell, 1-cell) pairs (prio tau = -inf) keyed by
/// (1-cell, 0-cell); phase-0 (1-cell, wedge) pairs (prio sigma = -inf) keyed by (rank of the
/// wedge by (prio, id), 1-cell); phase-1 pairs with their full key.
class Contraction {
 public:
  Contraction(const CellComplex& k, const Kept& kept, Index num_vertices, std::size_t np)
      : k_(k), kept_(kept), w_alive(k.num_wedges(), 1), e_alive(k.num_cells(), 1), v_alive(np, 0) {
    for (Index v = 0; v < num_vertices; ++v) v_alive[v] = 1;
    for (const Segment& e : k.ends) v_alive[e[0]] = v_alive[e[1]] = 1;
    e_count.resize(k.num_cells());
    v_count.resize(np);
    for (std::size_t e = 0; e < e_count.size(); ++e) e_count[e] = k.cof_begin[e + 1] - k.cof_begin[e];
    for (std::size_t v = 0; v < np; ++v) v_count[v] = k.inc_begin[v + 1] - k.inc_begin[v];
    rank_wedges();
  }

  void run() {
    const Index ne = static_cast<Index>(k_.num_cells()), np = static_cast<Index>(v_alive.size());
    for (Index e = 0; e < ne; ++e) try_edge_wedge(e);
    for (Index v = 0; v < np; ++v) try_vertex_edge(v);
    for (;;) {
      if (!vertex_pairs_.empty()) {
        const Key key = vertex_pairs_.top();
        vertex_pairs_.pop();
        collapse_vertex(static_cast<Index>(key & 0xffffffffu), static_cast<Index>(key >> 32));
      } else if (!wedge_pairs_.empty()) {
        const Key key = wedge_pairs_.top();
        wedge_pairs_.pop();
        collapse_wedge(static_cast<Index>(key & 0xffffffffu), wedge_of_rank_[key >> 32]);
      } else if (!curves_active_) {
        curves_active_ = true;
        for (Index e = 0; e < ne; ++e)
          if (k_.curve[e]) try_edge_wedge(e), try_vertex_edge(k_.ends[e][0]), try_vertex_edge(k_.ends[e][1]);
      } else if (!curve_pairs_.empty()) {
        const Pair p = curve_pairs_.top();
        curve_pairs_.pop();
        if (p.type == 0) collapse_wedge(p.sigma, p.tau);
        else collapse_vertex(p.sigma, p.tau);
      } else {
        break;
      }
    }
  }

  std::vector<char> w_alive, e_alive, v_alive;
  std::vector<Index> e_count, v_count;  ///< surviving cofaces of a 1-cell, of a point

 private:
  using Key = std::uint64_t;

  void rank_wedges() {
    const Index F = static_cast<Index>(k_.face_prio.size());
    const std::size_t nw = k_.num_wedges();
    wedge_rank_.resize(nw);
    std::vector<Index> faces(F);
    std::iota(faces.begin(), faces.end(), Index(0));
    std::sort(faces.begin(), faces.end(), [&](Index a, Index b) {
      return k_.face_prio[a] < k_.face_prio[b] || (k_.face_prio[a] == k_.face_prio[b] && a < b);
    });
    Index r = 0;
    for (Index f : faces)
      for (Index w = k_.face_wedge_begin[f]; w < k_.face_wedge_begin[f + 1]; ++w) wedge_rank_[w] = r++;
    wedge_of_rank_.resize(nw);
    for (Index w = 0; w < nw; ++w) wedge_of_rank_[wedge_rank_[w]] = w;
  }

  void try_edge_wedge(Index e) {
    if (!e_alive[e] || e_count[e] != 1 || kept_.e[e]) return;
    for (Index i = k_.cof_begin[e]; i < k_.cof_begin[e + 1]; ++i) {
      const Index w = k_.cof[i];
      if (!w_alive[w]) continue;
      if (kept_.w[w]) return;
      if (!k_.curve[e]) wedge_pairs_.push((Key(wedge_rank_[w]) << 32) | e);
      else if (curves_active_) curve_pairs_.push({1, k_.face_prio[k_.w_face[w]], k_.cell_prio[e], 0, e, w});
      return;
    }
  }

  void try_vertex_edge(Index v) {
    if (!v_alive[v] || v_count[v] != 1 || kept_.v[v]) return;
    for (Index i = k_.inc_begin[v]; i < k_.inc_begin[v + 1]; ++i) {
      const Index e = k_.inc[i];
      if (!e_alive[e]) continue;
      if (e_count[e] != 0 || kept_.e[e]) return;
      if (!k_.curve[e]) vertex_pairs_.push((Key(e) << 32) | v);
      else if (curves_active_) curve_pairs_.push({1, k_.cell_prio[e], kNegInf, 1, v, e});
      return;
    }
  }

  void collapse_wedge(Index e, Index w) {
    if (!w_alive[w] || !e_alive[e] || e_count[e] != 1) return;
    w_alive[w] = 0;
    e_alive[e] = 0;
    for (Index i = k_.w_bnd_begin[w]; i < k_.w_bnd_begin[w + 1]; ++i) --e_count[k_.w_bnd[i]];
    for (Index v : k_.ends[e]) --v_count[v];
    for (Index i = k_.w_bnd_begin[w]; i < k_.w_bnd_begin[w + 1]; ++i) {
      const Index e2 = k_.w_bnd[i];
      if (e2 == e || !e_alive[e2]) continue;
      if (e_count[e2] == 1) try_edge_wedge(e2);
      else if (e_count[e2] == 0) try_vertex_edge(k_.ends[e2][0]), try_vertex_edge(k_.ends[e2][1]);
    }
    for (Index v : k_.ends[e]) try_vertex_edge(v);
  }

  void collapse_vertex(Index v, Index e) {
    if (!v_alive[v] || !e_alive[e] || e_count[e] != 0 || v_count[v] != 1) return;
    v_alive[v] = 0;
    e_alive[e] = 0;
    v_count[v] = 0;
    const Index w = k_.ends[e][0] == v ? k_.ends[e][1] : k_.ends[e][0];
    --v_count[w];
    try_vertex_edge(w);
  }

  const CellComplex& k_;
  const Kept& kept_;
  std::vector<Index> wedge_rank_, wedge_of_rank_;
  std::priority_queue<Key, std::vector<Key>, std::greater<>> vertex_pairs_, wedge_pairs_;
  std::priority_queue<Pair, std::vector<Pair>, PairLater> curve_pairs_;
  // Phase-1 pairs are only queued once phase 0 has run dry (then every free one is found by a
  // scan): queued earlier, most would be stale by then and only slow the queue down.
  bool curves_active_ = false;
};

// ---- output --------------------------------------------------------------------------------------
// Coarsening: a triangle of the input whose wedges all survive is written as itself (or as a
// fan from its centre over the points its sides must keep), and a point on an edge whose
// triangles all survive whole is dropped: the same disk, the same topology, far fewer
// triangles. The other surviving wedges are written as fans from their face's dual point.

/// Per input triangle: all its wedges survive (and coarsening is on).
std::vector<char> whole_triangles(const TriangleComplex& cx, const Subdivision& sub, const CellComplex& k,
                                  const std::vector<char>& w_alive, bool coarsen) {
  const std::size_t nt = cx.num_triangles();
  std::vector<char> whole(nt, 0);
  if (!coarsen) return whole;
  for (std::size_t t = 0; t < nt; ++t) {
    bool all = true;
    for (Index f = sub.tri_face_begin[t]; f < sub.tri_face_begin[t + 1] && all; ++f)
      for (Index w = k.face_wedge_begin[f]; w < k.face_wedge_begin[f + 1] && all; ++w) all = w_alive[w];
    whole[t] = all;
  }
  return whole;
}

/// Per input edge: all its triangles are whole (its points can go).
std::vector<char> coarse_edges(const TriangleComplex& cx, const std::vector<char>& whole) {
  std::vector<char> coarse(cx.num_edges(), 0);
  for (std::size_t e = 0; e < cx.num_edges(); ++e) {
    bool all = true;
    for (Index i = cx.edge_tri_begin[e]; i < cx.edge_tri_begin[e + 1] && all; ++i) all = whole[cx.edge_tris[i]];
    coarse[e] = all;
  }
  return coarse;
}

/// Writes the surviving cells into a Skeleton.
class OutputWriter {
 public:
  OutputWriter(const BurnGraph& g, const Subdivision& sub, const CellComplex& k, const std::vector<double>& et_c,
               const Contraction& alive, Skeleton& out)
      : g_(g), sub_(sub), k_(k), et_c_(et_c), alive_(alive), out_(out), local_(sub.num_points(), kNone) {}

  /// Vertices left without edges (isolated input vertices, the point a component collapsed to).
  void isolated_points() {
    for (Index p = 0; p < sub_.num_points(); ++p)
      if (alive_.v_alive[p] && alive_.v_count[p] == 0) point(p);
  }

  /// The surviving wedges of triangle t, as fans from their face's dual point.
  void wedge_fans(Index t) {
    for (Index f = sub_.tri_face_begin[t]; f < sub_.tri_face_begin[t + 1]; ++f) {
      bool any = false;
      for (Index w = k_.face_wedge_begin[f]; w < k_.face_wedge_begin[f + 1] && !any; ++w) any = alive_.w_alive[w];
      if (!any) continue;
      face_boundary_points(sub_, f, ring_);
      const Index m = static_cast<Index>(ring_.size()), c = point(sub_.face_point(f));
      for (Index w = k_.face_wedge_begin[f]; w < k_.face_wedge_begin[f + 1]; ++w) {
        if (!alive_.w_alive[w]) continue;
        for (Index i = 0; i < k_.w_len[w]; ++i) {
          const Index r = (k_.w_first[w] + i) % m;
          out_.faces.push_back({c, point(ring_[r]), point(ring_[(r + 1) % m])});
          out_.face_priority.push_back(k_.face_prio[f]);
        }
      }
    }
  }

  /// Triangle t, whose wedges all survive: itself, or a fan from its centre over the points its
  /// sides keep (those on edges that are not coarse).
  void whole_triangle(Index t, const std::vector<char>& coarse_edge) {
    const double prio = whole_priority(t);
    const TriangleComplex& cx = *g_.cx;
    ring_.clear();
    for (int j = 0; j < 3; ++j) {
      ring_.push_back(cx.triangles[t][j]);
      const Index e = cx.tri_edges[t][j];
      if (coarse_edge[e]) continue;
      const Index n = g_.samples_on(e);
      const bool fwd = cx.side_forward(t, j);
      for (Index i = 0; i <= n; ++i) {
        if (i > 0) ring_.push_back(g_.side_node(t, j, i));
        const Index s = sub_.segment_begin[e] + (fwd ? i : n - i);
        if (sub_.segment_used[s]) ring_.push_back(sub_.segment_point(s));
      }
    }
    ++out_.coarse_triangles;
    if (ring_.size() == 3) {
      out_.faces.push_back({point(ring_[0]), point(ring_[1]), point(ring_[2])});
      out_.face_priority.push_back(prio);
      return;
    }
    const Index centre = centre_point(t);
    for (std::size_t i = 0; i < ring_.size(); ++i) {
      out_.faces.push_back({centre, point(ring_[i]), point(ring_[(i + 1) % ring_.size()])});
      out_.face_priority.push_back(prio);
    }
  }

  /// Edges: the sides of the written triangles and the surviving 1-cells that bound nothing.
  void edges() {
    auto key_of = [](Index a, Index b) {
      return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
    };
    std::vector<EdgeOut> eo;
    for (const Tri& t : out_.faces)
      for (int j = 0; j < 3; ++j) eo.push_back({key_of(t[j], t[(j + 1) % 3]), 0, kNegInf});
    std::vector<EdgeOut> curve_sides;  // surviving curve cells, to label the sides that are curve edges
    for (std::size_t e = 0; e < k_.num_cells(); ++e) {
      if (!alive_.e_alive[e]) continue;
      const Segment& ends = k_.ends[e];
      if (alive_.e_count[e] == 0) {
        eo.push_back({key_of(point(ends[0]), point(ends[1])), k_.curve[e], k_.cell_prio[e]});
      } else if (k_.curve[e] && local_[ends[0]] != kNone && local_[ends[1]] != kNone) {
        curve_sides.push_back({key_of(local_[ends[0]], local_[ends[1]]), 1, k_.cell_prio[e]});
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
      out_.edges.push_back({static_cast<Index>(e.key >> 32), static_cast<Index>(e.key & 0xffffffffu)});
      out_.edge_curve.push_back(e.curve);
      out_.edge_priority.push_back(e.prio);
    }
  }

 private:
  struct EdgeOut {
    std::uint64_t key;
    char curve;
    double prio;
  };

  /// The skeleton's index of subdivision point p (added on first use).
  Index point(Index p) {
    if (local_[p] != kNone) return local_[p];
    const Index N = sub_.num_nodes, S = sub_.num_segments;
    local_[p] = static_cast<Index>(out_.points.size());
    out_.points.push_back(sub_.point[p]);
    out_.radius.push_back(sub_.point_radius[p]);
    out_.bt.push_back(sub_.point_bt[p]);
    out_.et.push_back(sub_.point_et[p]);
    out_.et_c.push_back(et_c_[p]);
    out_.kind.push_back(p < N ? (g_.is_vertex(p) ? 0 : 1) : p < N + S ? 2 : 3);
    return local_[p];
  }

  /// Area-weighted priority of the whole triangle t.
  double whole_priority(Index t) const {
    double area = 0, weighted = 0;
    bool inf = false;
    for (Index f = sub_.tri_face_begin[t]; f < sub_.tri_face_begin[t + 1]; ++f)
      for (Index w = k_.face_wedge_begin[f]; w < k_.face_wedge_begin[f + 1]; ++w) {
        if (std::isinf(k_.face_prio[f])) inf = true;
        else area += k_.w_area[w], weighted += k_.w_area[w] * k_.face_prio[f];
      }
    return inf ? kInf : area > 0 ? weighted / area : k_.face_prio[sub_.tri_face_begin[t]];
  }

  /// A new point at the centre of triangle t (attributes: the mean of its corners').
  Index centre_point(Index t) {
    const Index centre = static_cast<Index>(out_.points.size());
    Vec3 c = Vec3::Zero();
    double r = 0, b = 0;
    for (Index v : g_.cx->triangles[t]) c += sub_.point[v], r += sub_.point_radius[v], b += sub_.point_bt[v];
    out_.points.push_back(c / 3);
    out_.radius.push_back(r / 3);
    out_.bt.push_back(b / 3);
    out_.et.push_back(std::isinf(b) ? kInf : (b - r) / 3);
    out_.et_c.push_back(std::numeric_limits<double>::quiet_NaN());
    out_.kind.push_back(4);
    return centre;
  }

  const BurnGraph& g_;
  const Subdivision& sub_;
  const CellComplex& k_;
  const std::vector<double>& et_c_;
  const Contraction& alive_;
  Skeleton& out_;
  std::vector<Index> local_, ring_;
};

void write_output(const BurnGraph& g, const Subdivision& sub, const CellComplex& k, const std::vector<double>& et_c,
                  const Contraction& alive, bool coarsen, Skeleton& out) {
  const TriangleComplex& cx = *g.cx;
  const std::vector<char> whole = whole_triangles(cx, sub, k, alive.w_alive, coarsen);
  const std::vector<char> coarse_edge = coarse_edges(cx, whole);
  OutputWriter writer(g, sub, k, et_c, alive, out);
  writer.isolated_points();
  for (Index t = 0; t < cx.num_triangles(); ++t) {
    if (whole[t]) writer.whole_triangle(t, coarse_edge);
    else writer.wedge_fans(t);
  }
  writer.edges();
}

}  // namespace

Skeleton compute_skeleton(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                          const SkeletonOptions& options) {
  const auto t0 = Clock::now();
  const std::vector<double> et_c = curve_erosion_thickness(sub);
  Skeleton out;
  const CellComplex k = build_cell_complex(g, sub, loose_edges, et_c);
  out.refined_faces = k.num_wedges();
  out.refined_edges = k.num_cells();
  out.seconds_refine = seconds_since(t0);

  const auto t1 = Clock::now();
  const Kept kept = protect(sub, k, options, out);
  out.seconds_protect = seconds_since(t1);

  Contraction contraction(k, kept, g.num_vertices(), sub.num_points());
  out.refined_vertices =
      static_cast<std::size_t>(std::count(contraction.v_alive.begin(), contraction.v_alive.end(), 1));
  contraction.run();
  out.seconds_contract = seconds_since(t1);

  const auto t2 = Clock::now();
  write_output(g, sub, k, et_c, contraction, options.coarsen, out);
  out.seconds_output = seconds_since(t2);
  return out;
}

}  // namespace medax::et
