// The output of et_skeleton. Coarsening: a triangle of the input whose wedges all survive is
// written as itself (or as a fan from its centre over the points its sides must keep), and a
// point on an edge whose triangles all survive whole is dropped: the same disk, the same
// topology, far fewer triangles. The other surviving wedges are written as fans from their
// face's dual point.
#include "skeleton_output.hpp"

#include <algorithm>
#include <cmath>

namespace medax::et::skeleton {

namespace {

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

}  // namespace

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

}  // namespace medax::et::skeleton
