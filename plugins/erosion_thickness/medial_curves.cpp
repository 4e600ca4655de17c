#include "medial_curves.hpp"

#include <medax/union_find.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace medax::et {

std::array<Index, 2> Subdivision::segment_nodes(const BurnGraph& g, Index s) const {
  const Index e = static_cast<Index>(std::upper_bound(segment_begin.begin(), segment_begin.end(), s) -
                                     segment_begin.begin()) - 1;
  const Index q = s - segment_begin[e], n = g.samples_on(e);
  const auto& ed = g.cx->edges[e];
  auto edge_node = [&](Index k) { return k == 0 ? ed[0] : k == n + 1 ? ed[1] : g.sample_begin[e] + (k - 1); };
  return {edge_node(q), edge_node(q + 1)};
}

namespace {

/// Weighted dual point (notes §5.2): sum BT_i p_i / sum BT_i; BT_M there is sum BT_i^2 / sum BT_i
/// and R the same weighted average of R_i. Uniform weights when a BT is inf or all are 0.
void dual_point(const BurnGraph& g, const std::vector<double>& bt, const Index* nodes, std::size_t n, Vec3& p,
                double& b, double& r) {
  double wsum = 0, b2 = 0;
  bool finite = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = bt[nodes[i]];
    if (!std::isfinite(w)) finite = false;
    wsum += w;
    b2 += w * w;
  }
  const bool uniform = !finite || !(wsum > 0);
  p.setZero();
  r = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = uniform ? 1.0 : bt[nodes[i]];
    p += w * g.pos[nodes[i]];
    r += w * g.radius[nodes[i]];
  }
  const double norm = uniform ? double(n) : wsum;
  p /= norm;
  r /= norm;
  b = !finite ? kInf : wsum > 0 ? b2 / wsum : 0.0;
}

// ---- segments and burn arcs ----------------------------------------------------------------------

/// Edge e has samples_on(e) + 1 segments, numbered edge by edge.
void number_segments(const BurnGraph& g, Subdivision& sub) {
  const std::size_t ne = g.cx->num_edges();
  sub.num_nodes = static_cast<Index>(g.num_nodes());
  sub.segment_begin.resize(ne + 1);
  Index S = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    sub.segment_begin[e] = S;
    S += g.samples_on(static_cast<Index>(e)) + 1;
  }
  sub.segment_begin[ne] = S;
  sub.num_segments = S;
}

/// The burn-tree arcs (primary arcs), grouped by their triangle: CSR.
struct TriangleArcs {
  std::vector<Index> begin;  ///< per triangle (+1)
  std::vector<Segment> arcs;  ///< (other end, node)
};

TriangleArcs arcs_by_triangle(const BurnGraph& g, const BurnResult& burn) {
  const std::size_t nt = g.cx->num_triangles();
  const Index N = static_cast<Index>(g.num_nodes());
  TriangleArcs a;
  a.begin.assign(nt + 1, 0);
  for (Index n = 0; n < N; ++n)
    for (Index s = g.sector_begin[n]; s < g.sector_begin[n + 1]; ++s)
      if (burn.prime_tri[s] != kNone) ++a.begin[burn.prime_tri[s] + 1];
  std::partial_sum(a.begin.begin(), a.begin.end(), a.begin.begin());
  a.arcs.resize(a.begin[nt]);
  std::vector<Index> fill(a.begin.begin(), a.begin.end() - 1);
  for (Index n = 0; n < N; ++n)
    for (Index s = g.sector_begin[n]; s < g.sector_begin[n + 1]; ++s)
      if (burn.prime_tri[s] != kNone) a.arcs[fill[burn.prime_tri[s]]++] = {burn.prime_node[s], n};
  return a;
}

// ---- faces: each triangle cut by its burn arcs ---------------------------------------------------

/// The two faces on the sides of a chord, and the chord's first end (a node).
struct Bridge {
  Index f1, f2, node;
};

/// Cuts the triangles into faces one at a time, appending them to the subdivision (scratch
/// vectors are reused between triangles).
class TriangleCutter {
 public:
  TriangleCutter(const BurnGraph& g, const BurnResult& burn, Subdivision& sub)
      : g_(g), cx_(*g.cx), burn_(burn), sub_(sub) {}

  /// Appends triangle t's faces and, per chord, its bridge to `bridges`.
  void cut(Index t, const TriangleArcs& arcs, std::vector<Bridge>& bridges) {
    make_polygon(t);
    bool residue = true;  // a triangle of a closed surface that never burns
    for (Index x : poly_) residue = residue && !std::isfinite(burn_.bt[x]);
    sub_.residue_triangles += residue;
    add_chords(t, arcs);
    walk_faces(t, residue);
    for (const auto& c : chords_) bridges.push_back({face_of(c[0], c[1]), face_of(c[1], c[0]), poly_[c[0]]});
    sub_.num_chords += static_cast<Index>(chords_.size());
  }

 private:
  /// Polygon of the triangle's nodes, in corner order, with the segment of each side.
  void make_polygon(Index t) {
    poly_.clear();
    poly_seg_.clear();
    for (int j = 0; j < 3; ++j) {
      off_[j] = static_cast<Index>(poly_.size());
      const Index e = cx_.tri_edges[t][j], n = g_.samples_on(e);
      const bool fwd = cx_.side_forward(t, j);
      for (Index k = 0; k <= n; ++k) {
        poly_.push_back(g_.side_node(t, j, k));
        poly_seg_.push_back(sub_.segment_begin[e] + (fwd ? k : n - k));
      }
    }
  }

  /// Position of a node of triangle t in its polygon.
  Index poly_index(Index t, Index node) const {
    const Tri& c = cx_.triangles[t];
    for (int j = 0; j < 3; ++j)
      if (c[j] == node) return off_[j];
    const Index e = g_.sample_edge[node - g_.num_vertices()];
    const auto& te = cx_.tri_edges[t];
    const int j = te[0] == e ? 0 : te[1] == e ? 1 : 2;
    const Index n = g_.samples_on(e), i = node - g_.sample_begin[e];
    return off_[j] + (cx_.side_forward(t, j) ? i + 1 : n - i);
  }

  /// The burn arcs of triangle t: edge-arcs cover a side, the others are chords (a chord that
  /// crosses an earlier one, by round-off, is dropped and counted).
  void add_chords(Index t, const TriangleArcs& arcs) {
    const Index P = static_cast<Index>(poly_.size());
    poly_covered_.assign(P, 0);
    chords_.clear();
    for (Index a = arcs.begin[t]; a < arcs.begin[t + 1]; ++a) {
      Index i = poly_index(t, arcs.arcs[a][0]), k = poly_index(t, arcs.arcs[a][1]);
      if (i > k) std::swap(i, k);
      if (k == i + 1) {
        poly_covered_[i] = 1;
        continue;
      }
      if (i == 0 && k == P - 1) {
        poly_covered_[P - 1] = 1;
        continue;
      }
      bool crosses = false;
      for (const auto& c : chords_)
        if ((c[0] < i && i < c[1] && c[1] < k) || (i < c[0] && c[0] < k && k < c[1])) crosses = true;
      if (crosses) {
        ++sub_.crossing_arcs;
        continue;
      }
      chords_.push_back({i, k});
    }
  }

  /// Faces: walk the planar graph of sides and chords of the convex polygon.
  void walk_faces(Index t, bool residue) {
    const Index P = static_cast<Index>(poly_.size());
    nbrs_.assign(P, {});
    for (Index i = 0; i < P; ++i) nbrs_[i].push_back((i + 1) % P), nbrs_[(i + 1) % P].push_back(i);
    for (const auto& c : chords_) nbrs_[c[0]].push_back(c[1]), nbrs_[c[1]].push_back(c[0]);
    directed_.clear();
    directed_face_.clear();
    for (Index i = 0; i < P; ++i)
      if (!visited(i, (i + 1) % P)) walk(t, residue, i, (i + 1) % P);
    for (const auto& c : chords_) {
      if (!visited(c[0], c[1])) walk(t, residue, c[0], c[1]);
      if (!visited(c[1], c[0])) walk(t, residue, c[1], c[0]);
    }
  }

  bool visited(Index a, Index b) const {
    return std::find(directed_.begin(), directed_.end(), std::pair<Index, Index>{a, b}) != directed_.end();
  }

  Index face_of(Index a, Index b) const {
    const auto it = std::find(directed_.begin(), directed_.end(), std::pair<Index, Index>{a, b});
    return directed_face_[it - directed_.begin()];
  }

  /// The face to the left of the directed side (a0, b0). At corner b, neighbours in
  /// counter-clockwise order have increasing offsets (c - b) mod P; arriving from a, the face
  /// continues to the neighbour with the largest offset below a's.
  void walk(Index t, bool residue, Index a0, Index b0) {
    const Index P = static_cast<Index>(poly_.size());
    face_.clear();
    Index a = a0, b = b0;
    do {
      directed_.push_back({a, b});
      directed_face_.push_back(static_cast<Index>(sub_.face_tri.size()));
      face_.push_back(a);
      const Index oa = (a + P - b) % P;
      Index best = kNone, best_off = 0;
      for (Index c : nbrs_[b]) {
        const Index oc = (c + P - b) % P;
        if (oc < oa && (best == kNone || oc > best_off)) best = c, best_off = oc;
      }
      a = b;
      b = best;
    } while (!(a == a0 && b == b0) && face_.size() <= 2 * P);
    emit_face(t, residue);
  }

  /// Appends the walked face: its corners and, per side, its segment (covered or not) or chord.
  void emit_face(Index t, bool residue) {
    const Index P = static_cast<Index>(poly_.size());
    sub_.face_tri.push_back(t);
    sub_.face_residue.push_back(residue);
    for (std::size_t k = 0; k < face_.size(); ++k) {
      const Index i = face_[k], j = face_[(k + 1) % face_.size()];
      sub_.corners.push_back(poly_[i]);
      if (j == (i + 1) % P) {
        sub_.side_segment.push_back(poly_seg_[i]);
        sub_.side_covered.push_back(poly_covered_[i]);
        sub_.side_chord.push_back(kNone);
      } else {
        sub_.side_segment.push_back(kNone);
        sub_.side_covered.push_back(0);
        const std::array<Index, 2> key{std::min(i, j), std::max(i, j)};
        const auto c = std::find(chords_.begin(), chords_.end(), key) - chords_.begin();
        sub_.side_chord.push_back(sub_.num_chords + static_cast<Index>(c));
      }
    }
    sub_.face_begin.push_back(static_cast<Index>(sub_.corners.size()));
  }

  const BurnGraph& g_;
  const TriangleComplex& cx_;
  const BurnResult& burn_;
  Subdivision& sub_;
  Index off_[3] = {0, 0, 0};                     // polygon position of each corner
  std::vector<Index> poly_;                      // polygon corners (node ids)
  std::vector<Index> poly_seg_;                  // side i (poly i -> i+1): segment id
  std::vector<char> poly_covered_;
  std::vector<std::array<Index, 2>> chords_;
  std::vector<std::vector<Index>> nbrs_;
  std::vector<std::pair<Index, Index>> directed_;  // visited directed edges (a, b)
  std::vector<Index> directed_face_;               // the face each one bounds
  std::vector<Index> face_;
};

// ---- the medial curves -----------------------------------------------------------------------------

/// The medial curves as the order complex of the cells that survive the cut (see the header):
/// faces, segments and unburned nodes, related by "lies on the boundary of", minus the
/// face-segment relations cut by a covering edge-arc.
class CurveLinker {
 public:
  CurveLinker(const BurnGraph& g, const BurnResult& burn, Subdivision& sub) : g_(g), burn_(burn), sub_(sub) {}

  void link() {
    sub_.segment_used.assign(sub_.num_segments, 0);
    for (Index f = 0; f < sub_.num_faces(); ++f) link_face(f);
    for (Index s : linked_) {
      const auto ends = sub_.segment_nodes(g_, s);
      for (Index p : ends)
        if (unburned(p)) sub_.curve_edges.push_back({sub_.segment_point(s), p});
    }
  }

 private:
  bool unburned(Index node) const { return !std::isfinite(burn_.bt[node]); }

  Index segment_edge(Index s) const {
    return static_cast<Index>(std::upper_bound(sub_.segment_begin.begin(), sub_.segment_begin.end(), s) -
                              sub_.segment_begin.begin()) - 1;
  }

  void use_segment(Index s) {
    if (!sub_.segment_used[s]) linked_.push_back(s);
    sub_.segment_used[s] = 1;
  }

  /// Face f's curve edges: to the segments on its boundary (a ∂M segment only when the face
  /// has no other connection) and to its unburned corners, with the closed-surface triangles.
  void link_face(Index f) {
    const Index b = sub_.face_begin[f], m = sub_.face_begin[f + 1] - b;
    const Index fp = sub_.face_point(f);
    std::size_t connections = 0;
    Index boundary_fallback = kNone;
    for (Index k = 0; k < m; ++k) {
      const Index s = sub_.side_segment[b + k];
      if (s == kNone || sub_.side_covered[b + k]) continue;
      const Index p0 = sub_.corners[b + k], p1 = sub_.corners[b + (k + 1) % m];
      const bool open_end = unburned(p0) || unburned(p1);
      if (g_.cx->edge_degree(segment_edge(s)) == 1 && !open_end) {
        if (boundary_fallback == kNone) boundary_fallback = s;  // a leaf: skipped unless needed
        continue;
      }
      sub_.curve_edges.push_back({fp, sub_.segment_point(s)});
      use_segment(s);
      ++connections;
      for (Index p : {p0, p1})
        if (unburned(p)) sub_.curve_triangles.push_back({fp, sub_.segment_point(s), p});
    }
    for (Index k = 0; k < m; ++k)
      if (unburned(sub_.corners[b + k])) {
        sub_.curve_edges.push_back({fp, sub_.corners[b + k]});
        ++connections;
      }
    if (connections > 0) return;
    if (boundary_fallback == kNone) {
      ++sub_.unconnected_faces;
      return;
    }
    sub_.curve_edges.push_back({fp, sub_.segment_point(boundary_fallback)});
    use_segment(boundary_fallback);
  }

  const BurnGraph& g_;
  const BurnResult& burn_;
  Subdivision& sub_;
  std::vector<Index> linked_;  // segments joined to a face, for the segment-node edges
};

/// Bridges. The cut can split off a piece that the rest of M reaches only across a burn arc or
/// through a node: an arc from a ∂M node to a node that is on ∂M but also on a seam (so not on
/// ∂G) cuts off a corner bounded by ∂M alone, and a vertex whose link is disconnected (two
/// sheets touching at a point) joins sheets only through itself. Such a piece is an extra
/// component of C. Join the components again, without closing any cycle: across a chord
/// (face - chord end - face), then through shared nodes (face - node - face), each only when
/// its two faces are in different components.
void add_bridges(const std::vector<Bridge>& chord_bridges, Subdivision& sub) {
  const Index N = sub.num_nodes, F = sub.num_faces();
  const std::size_t npoints = std::size_t(N) + sub.num_segments + F;
  UnionFind uf(npoints);
  std::vector<char> in_c(npoints, 0);
  for (const Segment& e : sub.curve_edges) uf.unite(e[0], e[1]), in_c[e[0]] = in_c[e[1]] = 1;
  for (const Tri& t : sub.curve_triangles) uf.unite(t[0], t[1]), uf.unite(t[1], t[2]);
  for (Index f = 0; f < F; ++f) in_c[sub.face_point(f)] = 1;
  auto bridge = [&](Index f1, Index f2, Index node) {
    const Index a = sub.face_point(f1), b = sub.face_point(f2);
    if (uf.find(a) == uf.find(b)) return;
    if (!in_c[node] || (uf.find(node) != uf.find(a) && uf.find(node) != uf.find(b))) {
      sub.curve_edges.push_back({a, node});
      sub.curve_edges.push_back({node, b});
    } else {
      sub.curve_edges.push_back(uf.find(node) == uf.find(a) ? Segment{node, b} : Segment{a, node});
    }
    in_c[node] = 1;
    uf.unite(a, node);
    uf.unite(node, b);
    ++sub.bridges;
  };
  for (const Bridge& br : chord_bridges) bridge(br.f1, br.f2, br.node);
  // Faces around each node, in face order.
  std::vector<Index> first_face(N, kNone);
  for (Index f = 0; f < F; ++f)
    for (Index k = sub.face_begin[f]; k < sub.face_begin[f + 1]; ++k) {
      const Index p = sub.corners[k];
      if (first_face[p] == kNone) first_face[p] = f;
      else bridge(first_face[p], f, p);
    }
}

/// Positions, BT_M, R and ET_M of every point: the nodes', and the dual points' (NaN for a
/// segment without one).
void place_points(const BurnGraph& g, const BurnResult& burn, Subdivision& sub) {
  const Index N = sub.num_nodes, S = sub.num_segments, F = sub.num_faces();
  const std::size_t npoints = std::size_t(N) + S + F;
  sub.point.resize(npoints);
  sub.point_bt.resize(npoints);
  sub.point_radius.resize(npoints);
  for (Index n = 0; n < N; ++n) {
    sub.point[n] = g.pos[n];
    sub.point_bt[n] = burn.bt[n];
    sub.point_radius[n] = g.radius[n];
  }
  for (Index s = 0; s < S; ++s) {
    const Index p = sub.segment_point(s);
    if (!sub.segment_used[s]) {
      sub.point[p] = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
      sub.point_bt[p] = sub.point_radius[p] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const auto ends = sub.segment_nodes(g, s);
    dual_point(g, burn.bt, ends.data(), 2, sub.point[p], sub.point_bt[p], sub.point_radius[p]);
  }
  for (Index f = 0; f < F; ++f) {
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    const Index p = sub.face_point(f);
    dual_point(g, burn.bt, &sub.corners[b], m, sub.point[p], sub.point_bt[p], sub.point_radius[p]);
  }
  sub.point_et.resize(npoints);
  for (std::size_t p = 0; p < npoints; ++p)
    sub.point_et[p] = std::isinf(sub.point_bt[p]) ? kInf : sub.point_bt[p] - sub.point_radius[p];
}

}  // namespace

Subdivision build_subdivision(const BurnGraph& g, const BurnResult& burn) {
  const Index nt = static_cast<Index>(g.cx->num_triangles());
  Subdivision sub;
  number_segments(g, sub);
  const TriangleArcs arcs = arcs_by_triangle(g, burn);
  std::vector<Bridge> chord_bridges;
  sub.tri_face_begin.assign(nt + 1, 0);
  sub.face_begin.push_back(0);
  TriangleCutter cutter(g, burn, sub);
  for (Index t = 0; t < nt; ++t) {
    sub.tri_face_begin[t] = static_cast<Index>(sub.face_tri.size());
    cutter.cut(t, arcs, chord_bridges);
  }
  sub.tri_face_begin[nt] = static_cast<Index>(sub.face_tri.size());
  CurveLinker(g, burn, sub).link();
  add_bridges(chord_bridges, sub);
  place_points(g, burn, sub);
  return sub;
}

void face_boundary_points(const Subdivision& sub, Index f, std::vector<Index>& out) {
  out.clear();
  for (Index k = sub.face_begin[f]; k < sub.face_begin[f + 1]; ++k) {
    out.push_back(sub.corners[k]);
    const Index s = sub.side_segment[k];
    if (s != kNone && sub.segment_used[s]) out.push_back(sub.segment_point(s));
  }
}

std::vector<double> curve_erosion_thickness(const Subdivision& sub, std::vector<double>* bt_c) {
  // Unburned nodes (closed surfaces) never burn: they anchor what hangs off them.
  // The 1D burn on C, over the points that C uses.
  const std::size_t np = sub.num_points();
  std::vector<Index> local(np, kNone), global;
  for (const Segment& e : sub.curve_edges)
    for (Index p : e)
      if (local[p] == kNone) local[p] = static_cast<Index>(global.size()), global.push_back(p);
  Graph1D c;
  for (Index p : global) {
    c.points.push_back(sub.point[p]);
    c.ignite.push_back(sub.point_bt[p]);
    c.anchored.push_back(p < sub.num_nodes && std::isinf(sub.point_bt[p]));
  }
  for (const Segment& e : sub.curve_edges) c.edges.push_back({local[e[0]], local[e[1]]});
  const std::vector<double> bt = burn_1d(c);
  std::vector<double> et(np, std::numeric_limits<double>::quiet_NaN());
  if (bt_c) bt_c->assign(np, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < global.size(); ++i) {
    const Index p = global[i];
    et[p] = std::isinf(bt[i]) || std::isinf(sub.point_bt[p]) ? kInf : bt[i] - sub.point_bt[p];
    if (bt_c) (*bt_c)[p] = bt[i];
  }
  return et;
}

MedialCurves extract_medial_curves(const BurnGraph& g, const Subdivision& sub) {
  std::vector<double> bt_c;
  const std::vector<double> et_c = curve_erosion_thickness(sub, &bt_c);
  MedialCurves out;
  std::vector<Index> local(sub.num_points(), kNone);
  auto vertex = [&](Index p) {
    if (local[p] != kNone) return local[p];
    local[p] = static_cast<Index>(out.points.size());
    out.points.push_back(sub.point[p]);
    out.radius.push_back(sub.point_radius[p]);
    out.bt_m.push_back(sub.point_bt[p]);
    out.bt_c.push_back(bt_c[p]);
    out.et_c.push_back(et_c[p]);
    out.source.push_back(p);
    const int kind = p < sub.num_nodes ? (g.is_vertex(p) ? 0 : 1) : p < sub.num_nodes + sub.num_segments ? 2 : 3;
    out.kind.push_back(kind);
    return local[p];
  };
  for (const Segment& e : sub.curve_edges) out.edges.push_back({vertex(e[0]), vertex(e[1])});
  for (const Tri& t : sub.curve_triangles) out.faces.push_back({vertex(t[0]), vertex(t[1]), vertex(t[2])});
  // Off the 1D part (closed surfaces), ET_C is infinite like ET.
  for (std::size_t i = 0; i < out.et_c.size(); ++i)
    if (std::isnan(out.et_c[i]) && std::isinf(out.bt_m[i])) out.et_c[i] = kInf;
  return out;
}

}  // namespace medax::et
