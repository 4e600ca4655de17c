#include <medax/services/envelope.hpp>

#include <medax/services/kdtree.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace medax::services {

double EnvelopeSamples::total_area() const { return std::accumulate(areas.begin(), areas.end(), 0.0); }

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The value of one primitive at a point and the interpolated ball realising it.
struct Eval {
  double d = kInf;
  Vec3 c = Vec3::Zero();
  double r = 0;
};

inline double sphere_value(const Vec3& x, const Vec3& c, double r) { return (x - c).norm() - r; }

/// What a cone's closed form needs beyond its two balls.
struct ConeFrame {
  double length = 0, inv_length = 0, k = 0;
  double q = 0;  ///< √(1 − k²); 0 when one ball contains the other (|k| ≥ 1) or c0 = c1

  ConeFrame() = default;
  ConeFrame(const Vec3& c0, double r0, const Vec3& c1, double r1) {
    length = (c1 - c0).norm();
    if (!(length > 0)) return;
    inv_length = 1 / length;
    k = (r1 - r0) / length;
    if (!(std::abs(k) < 1)) return;
    q = std::sqrt(1 - k * k);
  }
};

// min over t of |x − c(t)| − r(t) along a cone. With s the axial coordinate of x from c0, ρ its
// distance to the axis and k = (r1 − r0)/L the slope, the objective sqrt((s − t)² + ρ²) − r0 − k·t
// is convex in t; its stationary point is t* = s + kρ/√(1−k²), where it equals
// ρ√(1−k²) − r0 − k·s. When t* leaves [0, L] (or |k| ≥ 1) the minimum is at an end ball.
template <bool kFull>
inline double cone_value(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1, const ConeFrame& f,
                         Eval* out) {
  const Vec3 w = x - c0;
  if (f.q > 0) {
    const Vec3 u = (c1 - c0) * f.inv_length;
    const double s = w.dot(u);
    const double rho = w.cross(u).norm();
    const double t = s + f.k * rho / f.q;
    if (t > 0 && t < f.length) {
      const double d = rho * f.q - r0 - f.k * s;
      if constexpr (kFull) *out = {d, c0 + t * u, r0 + f.k * t};
      return d;
    }
    // Convex with its minimum beyond an end: that end.
    if (t <= 0) {
      const double d = w.norm() - r0;
      if constexpr (kFull) *out = {d, c0, r0};
      return d;
    }
    const double d = sphere_value(x, c1, r1);
    if constexpr (kFull) *out = {d, c1, r1};
    return d;
  }
  const double d0 = w.norm() - r0, d1 = sphere_value(x, c1, r1);
  if constexpr (kFull) *out = d0 <= d1 ? Eval{d0, c0, r0} : Eval{d1, c1, r1};
  return std::min(d0, d1);
}

/// What a slab's closed form needs: the plane, the in-plane radius gradient g and the dual basis
/// giving barycentric coordinates. For |g| < 1 and x at height h over the plane (foot y_x), the
/// convex objective sqrt(|y − y_x|² + h²) − r(y) has its unique minimiser at
/// y* = y_x + |h|/√(1−|g|²)·g, with value |h|√(1−|g|²) − r(y_x). If y* leaves the triangle (or
/// |g| ≥ 1, or the triangle is degenerate) the minimum is on a side.
struct SlabFrame {
  Vec3 n = Vec3::Zero(), g = Vec3::Zero(), d1 = Vec3::Zero(), d2 = Vec3::Zero();
  double q = 0;  ///< √(1 − |g|²); 0 when there is no interior minimiser (degenerate, |g| ≥ 1)

  SlabFrame() = default;
  SlabFrame(const Vec3& c0, double r0, const Vec3& c1, double r1, const Vec3& c2, double r2) {
    const Vec3 e1 = c1 - c0, e2 = c2 - c0;
    const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2);
    const double det = a * c - b * b;
    if (!(det > 1e-14 * a * c)) return;
    d1 = (c * e1 - b * e2) / det;  // barycentric u = (y − c0)·d1, v = (y − c0)·d2
    d2 = (a * e2 - b * e1) / det;
    g = (r1 - r0) * d1 + (r2 - r0) * d2;
    const double g2 = g.squaredNorm();
    if (!(g2 < 1)) return;
    n = e1.cross(e2).normalized();
    q = std::sqrt(1 - g2);
  }
};

/// Geometry of one primitive, stored inline in BVH order.
struct PrimGeom {
  std::array<Vec3, 3> c;
  std::array<double, 3> r;
  int count = 1;
  std::array<ConeFrame, 3> edge;  // cone: edge[0]; slab: (0,1), (1,2), (2,0)
  SlabFrame slab;

  void init() {
    if (count == 2) {
      edge[0] = ConeFrame(c[0], r[0], c[1], r[1]);
    } else if (count == 3) {
      for (int k = 0; k < 3; ++k) edge[k] = ConeFrame(c[k], r[k], c[(k + 1) % 3], r[(k + 1) % 3]);
      slab = SlabFrame(c[0], r[0], c[1], r[1], c[2], r[2]);
    }
  }

  template <bool kFull>
  double eval(const Vec3& x, Eval* out) const {
    if (count == 1) {
      const double d = sphere_value(x, c[0], r[0]);
      if constexpr (kFull) *out = {d, c[0], r[0]};
      return d;
    }
    if (count == 2) return cone_value<kFull>(x, c[0], r[0], c[1], r[1], edge[0], out);
    // Edges to try when the minimiser is not inside: all three, or, when the unconstrained
    // minimiser y* exists, only the sides whose line separates y* from the triangle (a side
    // facing away from y* cannot hold the constrained minimum of a convex function: the segment
    // from such a point towards y* enters the triangle and descends).
    bool visible[3] = {true, true, true};
    if (slab.q > 0) {
      const Vec3 w = x - c[0];
      const double h = w.dot(slab.n);
      const Vec3 y = (w - h * slab.n) + (std::abs(h) / slab.q) * slab.g;  // relative to c0
      const double u = y.dot(slab.d1), v = y.dot(slab.d2);
      if (u >= 0 && v >= 0 && u + v <= 1) {
        const double d = std::abs(h) * slab.q - (r[0] + slab.g.dot(w));
        if constexpr (kFull) *out = {d, c[0] + y, r[0] + u * (r[1] - r[0]) + v * (r[2] - r[0])};
        return d;
      }
      visible[0] = v < 0;          // side (0, 1), opposite vertex 2
      visible[1] = u + v > 1;      // side (1, 2), opposite vertex 0
      visible[2] = u < 0;          // side (2, 0), opposite vertex 1
    }
    Eval e[3];
    double best = kInf;
    int arg = 0;
    for (int k = 0; k < 3; ++k) {
      if (!visible[k]) continue;
      const int j = (k + 1) % 3;
      const double d = cone_value<kFull>(x, c[k], r[k], c[j], r[j], edge[k], &e[k]);
      if (d < best) {
        best = d;
        arg = k;
      }
    }
    if constexpr (kFull) *out = e[arg];
    return best;
  }

  Eval full(const Vec3& x) const {
    Eval e;
    eval<true>(x, &e);
    return e;
  }
};

inline PrimGeom make_prim(int count, const std::array<Vec3, 3>& c, const std::array<double, 3>& r) {
  PrimGeom p;
  p.count = count;
  p.c = c;
  p.r = r;
  p.init();
  return p;
}

struct Box {
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void add(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
};

/// A BVH node over primitives, with two lower bounds on sd_P(x) for every primitive P below it
/// (every interpolated ball (c, r) of P has c in the centre box, r ≤ r_max, and, by linearity,
/// r ≤ ℓ(c) for an affine fit ℓ of the node's vertex radii):
///   sd_P(x) ≥ dist(x, centre box) − r_max,
///   sd_P(x) ≥ |x − c| − ℓ(c) ≥ (1 − |g|)·dist(x, centre box) − g·x + gamma  (|g| < 1),
/// where ℓ(c) = g·c − gamma.
/// The affine bound is what makes long primitives whose radius grows along them (Voronoi faces
/// running from the surface to the medial axis) cheap to prune: r_max alone is the radius at
/// their far end. A node's left child follows it; its right child follows the left subtree.
struct Node {
  // Single precision, rounded outwards so that the bounds stay valid: half the memory a query
  // reads.
  std::array<float, 3> lo, hi;  // centre box
  std::array<float, 3> g;
  float rmax = 0, slope = 0, gamma = 0;  // every ball below: r ≤ g·c − gamma; slope ≥ |g|
  std::uint32_t first = 0;  ///< leaf: first primitive; inner: index of the right child (left = next)
  std::uint32_t count = 0;  ///< leaf: number of primitives; inner: 0

  double lower_bound(const Vec3& x) const {
    double d2 = 0, gx = 0;
    for (int k = 0; k < 3; ++k) {
      const double below = double(lo[k]) - x[k], above = x[k] - double(hi[k]);
      const double out = std::max(0.0, std::max(below, above));
      d2 += out * out;
      gx += double(g[k]) * x[k];
    }
    const double d = std::sqrt(d2);
    return std::max(d - double(rmax), (1 - double(slope)) * d - gx + double(gamma));
  }
};

inline float round_down(double v) {
  const float f = static_cast<float>(v);
  return double(f) <= v ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
inline float round_up(double v) {
  const float f = static_cast<float>(v);
  return double(f) >= v ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

/// Sums over vertex balls (c, r): count, Σc, Σccᵀ, Σr, Σcr.
struct Moments {
  double n = 0, r = 0;
  Vec3 c = Vec3::Zero(), cr = Vec3::Zero();
  Eigen::Matrix3d cc = Eigen::Matrix3d::Zero();
  void add(const Vec3& centre, double radius) {
    n += 1;
    r += radius;
    c += centre;
    cr += radius * centre;
    cc += centre * centre.transpose();
  }
  Moments& operator+=(const Moments& o) {
    n += o.n;
    r += o.r;
    c += o.c;
    cr += o.cr;
    cc += o.cc;
    return *this;
  }
};

constexpr std::uint32_t kLeafSize = 2;  // primitives per leaf (2 measured best, 1 as good, 4 and 8 worse)
constexpr int kLastLevel = 2;           // octree cells of 4×4×4 steps, then grid points (2 measured best)


}  // namespace

struct Envelope::Impl {
  std::vector<EnvelopePrimitive> primitives;  // public order
  std::vector<PrimGeom> geometry;             // BVH order
  std::vector<Index> public_index;            // BVH order -> public order
  std::vector<Index> bvh_index;               // public order -> BVH order
  std::vector<Node> nodes;
  Box bounds;

  /// Per-primitive data for building: split keys, centre box, largest radius, and the moments
  /// of its vertex balls (additive, so that a node's radius fit comes from its children's).
  struct BuildItem {
    std::array<double, 4> key;  // centre-box midpoint, 2·r_max (ball sizes grouped too)
    std::array<Eigen::Matrix<double, 4, 1, Eigen::DontAlign>, 3> balls;  // (c, r) of its vertices
    int count = 0;
    Box box;
    double rmax = 0;
    Moments moments;
  };

  /// Builds the subtree of primitives order[begin, end) at node `id`; a subtree of n primitives
  /// owns the 2n − 1 node slots from `id` (left child at id + 1, right child after the left
  /// subtree's slots), so that subtrees can be built in parallel. Returns the subtree's moments.
  Moments build(std::uint32_t id, std::vector<Index>& order, const std::vector<BuildItem>& items, std::uint32_t begin,
                std::uint32_t end) {
    Node& node = nodes[id];
    if (end - begin <= kLeafSize) {
      Box box;
      double radius = 0;
      Moments m;
      for (std::uint32_t i = begin; i < end; ++i) {
        box.add(items[order[i]].box);
        radius = std::max(radius, items[order[i]].rmax);
        m += items[order[i]].moments;
      }
      set_bounds(node, box, radius);
      const Vec3 g = fit_slope(node, m);
      node.gamma = round_down(-max_offset(g, order, items, begin, end));
      node.first = begin;
      node.count = end - begin;
      return m;
    }
    // Split along the widest of the four keys, at the middle of its range (object median when
    // that leaves a side empty).
    double lo4[4], hi4[4];
    for (int a = 0; a < 4; ++a) lo4[a] = kInf, hi4[a] = -kInf;
    for (std::uint32_t i = begin; i < end; ++i)
      for (int a = 0; a < 4; ++a) {
        lo4[a] = std::min(lo4[a], items[order[i]].key[a]);
        hi4[a] = std::max(hi4[a], items[order[i]].key[a]);
      }
    int axis = 0;
    for (int a = 1; a < 4; ++a)
      if (hi4[a] - lo4[a] > hi4[axis] - lo4[axis]) axis = a;
    const double split = 0.5 * (lo4[axis] + hi4[axis]);
    std::uint32_t mid = static_cast<std::uint32_t>(
        std::stable_partition(order.begin() + begin, order.begin() + end,
                              [&](Index p) { return items[p].key[axis] < split; }) -
        order.begin());
    if (mid == begin || mid == end) {
      mid = begin + (end - begin) / 2;
      std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](Index p, Index q) {
        const double mp = items[p].key[axis], mq = items[q].key[axis];
        return mp < mq || (mp == mq && p < q);
      });
    }
    const std::uint32_t left = id + 1, right = id + 2 * (mid - begin);
    Moments ml, mr;
    if (end - begin > 8192) {
      tbb::parallel_invoke([&] { ml = build(left, order, items, begin, mid); },
                           [&] { mr = build(right, order, items, mid, end); });
    } else {
      ml = build(left, order, items, begin, mid);
      mr = build(right, order, items, mid, end);
    }
    const Node& a = nodes[left];
    const Node& b = nodes[right];
    Box box;
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min(a.lo[k], b.lo[k]);
      box.hi[k] = std::max(a.hi[k], b.hi[k]);
    }
    set_bounds(node, box, std::max(double(a.rmax), double(b.rmax)));
    Moments m = ml;
    m += mr;
    const Vec3 g = fit_slope(node, m);
    node.gamma = round_down(-max_offset(g, order, items, begin, end));
    node.first = right;
    node.count = 0;
    return m;
  }

  /// max over the vertex balls below of r − g·c.
  static double max_offset(const Vec3& g, const std::vector<Index>& order, const std::vector<BuildItem>& items,
                           std::uint32_t begin, std::uint32_t end) {
    double offset = -kInf;
    for (std::uint32_t i = begin; i < end; ++i) {
      const BuildItem& item = items[order[i]];
      for (int k = 0; k < item.count; ++k) offset = std::max(offset, item.balls[k][3] - g.dot(item.balls[k].head<3>()));
    }
    return offset;
  }

  static void set_bounds(Node& node, const Box& box, double radius) {
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = round_down(box.lo[k]);
      node.hi[k] = round_up(box.hi[k]);
    }
    node.rmax = round_up(radius);
  }

  /// Least-squares slope g of r ≈ r̄ + g·(c − c̄) over the balls the moments describe, capped
  /// below 1 and rounded to what the node stores; sets node.g and node.slope, returns g.
  static Vec3 fit_slope(Node& node, const Moments& m) {
    Vec3 g = Vec3::Zero();
    if (m.n > 1) {
      const Vec3 mean = m.c / m.n;
      Eigen::Matrix3d a = m.cc / m.n - mean * mean.transpose();
      const Vec3 b = m.cr / m.n - mean * (m.r / m.n);
      a += (1e-12 * (a.trace() + 1e-300)) * Eigen::Matrix3d::Identity();
      g = a.ldlt().solve(b);
      if (!g.allFinite()) g = Vec3::Zero();
      const double slope = g.norm();
      constexpr double kMaxSlope = 0.95;
      if (slope > kMaxSlope) g *= kMaxSlope / slope;
    }
    for (int k = 0; k < 3; ++k) {
      node.g[k] = static_cast<float>(g[k]);
      g[k] = double(node.g[k]);  // the bound is exact for whatever g is stored
    }
    node.slope = round_up(g.norm());
    return g;
  }

  struct Hit {
    double d;
    std::int64_t prim;  ///< BVH-order index, −1 when nothing below `upper` was found
  };

  /// min over primitives of sd_P(x). Values ≥ `upper` are not reported (the result is then
  /// {upper, −1}); the search stops as soon as a value below `stop_below` is found (the result is
  /// then an upper bound on φ(x), below stop_below). Once a value ≤ `settle` is found, only the
  /// question "is φ(x) < stop_below?" is pursued (nodes are pruned at stop_below): the result is
  /// then not exact, only φ(x) ∈ [stop_below, result]. `start` (a primitive and its value at x,
  /// e.g. from a neighbouring query) seeds the search.
  Hit query(const Vec3& x, double upper = kInf, double stop_below = -kInf, double settle = -kInf,
            Hit start = {kInf, -1}) const {
    Hit best = start.prim >= 0 && start.d < upper ? start : Hit{upper, -1};
    if (best.d < stop_below) return best;
    double bound = best.prim >= 0 && best.d <= settle ? stop_below : best.d;  // prune what cannot go below
    if (nodes.empty()) return best;
    struct Item {
      std::uint32_t node;
      double lb;
    };
    Item stack[128];
    int top = 0;
    const double lb_root = nodes[0].lower_bound(x);
    if (lb_root < bound) stack[top++] = {0, lb_root};
    while (top > 0) {
      const Item item = stack[--top];
      if (item.lb >= bound) continue;
      const Node& node = nodes[item.node];
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
          const double d = geometry[i].eval<false>(x, nullptr);
          if (d < best.d) {
            best = {d, static_cast<std::int64_t>(i)};
            if (best.d < stop_below) return best;
            bound = best.d <= settle ? stop_below : best.d;
          }
        }
        continue;
      }
      const std::uint32_t left = item.node + 1, right = node.first;
      const double lb_left = nodes[left].lower_bound(x), lb_right = nodes[right].lower_bound(x);
      // Push the farther child first so that the nearer one is explored first.
      if (lb_left <= lb_right) {
        if (lb_right < bound) stack[top++] = {right, lb_right};
        if (lb_left < bound) stack[top++] = {left, lb_left};
      } else {
        if (lb_left < bound) stack[top++] = {left, lb_left};
        if (lb_right < bound) stack[top++] = {right, lb_right};
      }
    }
    return best;
  }

  /// The interpolated ball of primitive `prim` (BVH order) realising its value at x.
  Eval ball(const Vec3& x, std::int64_t prim) const { return geometry[static_cast<std::size_t>(prim)].full(x); }
};

Envelope::Envelope(const MedialComplex& medial) : impl_(std::make_unique<Impl>()) {
  const std::size_t nv = medial.num_vertices();
  if (medial.radii.size() != nv)
    throw std::invalid_argument("envelope: the medial complex has " + std::to_string(nv) + " centres but " +
                                std::to_string(medial.radii.size()) + " radii");
  const auto check = [nv](Index v, const char* kind, std::size_t i) {
    if (v >= nv)
      throw std::invalid_argument(std::string("envelope: ") + kind + " " + std::to_string(i) +
                                  " refers to vertex " + std::to_string(v) + " of " + std::to_string(nv));
  };
  // Maximal elements: distinct non-degenerate triangles; edges (explicit ones and degenerate
  // triangles) that are no triangle's side; vertices in no edge or triangle.
  using Key3 = std::array<Index, 3>;
  std::vector<std::pair<Key3, Index>> tris;
  std::vector<std::pair<std::array<Index, 2>, std::pair<Element, Index>>> segs;
  std::vector<char> covered(nv, 0);
  for (std::size_t f = 0; f < medial.faces.size(); ++f) {
    Key3 k = medial.faces[f];
    for (Index v : k) check(v, "face", f);
    std::sort(k.begin(), k.end());
    if (k[0] != k[1] && k[1] != k[2]) {
      tris.push_back({k, static_cast<Index>(f)});
    } else if (k[0] != k[2]) {
      segs.push_back({{k[0], k[2]}, {Element::Face, static_cast<Index>(f)}});
    }
    for (Index v : k) covered[v] = 1;
  }
  for (std::size_t e = 0; e < medial.edges.size(); ++e) {
    const Segment& s = medial.edges[e];
    for (Index v : s) check(v, "edge", e);
    if (s[0] != s[1]) {
      segs.push_back({{std::min(s[0], s[1]), std::max(s[0], s[1])}, {Element::Edge, static_cast<Index>(e)}});
      covered[s[0]] = covered[s[1]] = 1;
    }
  }
  std::stable_sort(tris.begin(), tris.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  tris.erase(std::unique(tris.begin(), tris.end(), [](const auto& p, const auto& q) { return p.first == q.first; }),
             tris.end());
  std::vector<std::array<Index, 2>> sides;
  sides.reserve(3 * tris.size());
  for (const auto& [k, f] : tris) sides.insert(sides.end(), {{k[0], k[1]}, {k[1], k[2]}, {k[0], k[2]}});
  std::sort(sides.begin(), sides.end());
  std::stable_sort(segs.begin(), segs.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  segs.erase(std::unique(segs.begin(), segs.end(), [](const auto& p, const auto& q) { return p.first == q.first; }),
             segs.end());

  auto& prims = impl_->primitives;
  for (Index v = 0; v < nv; ++v)
    if (!covered[v]) prims.push_back({1, {v, v, v}, Element::Vertex, v});
  for (const auto& [k, origin] : segs)
    if (!std::binary_search(sides.begin(), sides.end(), k))
      prims.push_back({2, {k[0], k[1], k[1]}, origin.first, origin.second});
  for (const auto& [k, f] : tris) prims.push_back({3, k, Element::Face, f});

  // Per-primitive boxes, then the hierarchy.
  const std::size_t np = prims.size();
  if (np > std::numeric_limits<std::uint32_t>::max() / 2)
    throw std::invalid_argument("envelope: too many primitives");
  for (const EnvelopePrimitive& p : prims)
    for (int k = 0; k < p.count; ++k) {
      const Index v = p.vertices[k];
      if (!medial.centres[v].allFinite() || !std::isfinite(medial.radii[v]) || medial.radii[v] < 0)
        throw std::invalid_argument("envelope: vertex " + std::to_string(v) + " has a non-finite centre or an "
                                    "invalid radius");
    }
  std::vector<PrimGeom>& geometry = impl_->geometry;
  geometry.resize(np);
  std::vector<Impl::BuildItem> items(np);
  tbb::parallel_for(std::size_t{0}, np, [&](std::size_t i) {
    const EnvelopePrimitive& p = prims[i];
    std::array<Vec3, 3> c;
    std::array<double, 3> r;
    Impl::BuildItem& item = items[i];
    for (int k = 0; k < 3; ++k) {
      const Index v = p.vertices[std::min(k, p.count - 1)];
      c[k] = medial.centres[v];
      r[k] = medial.radii[v];
      if (k < p.count) {
        item.balls[k] << c[k], r[k];
        item.box.add(c[k]);
        item.rmax = std::max(item.rmax, r[k]);
        item.moments.add(c[k], r[k]);
      }
    }
    item.count = p.count;
    geometry[i] = make_prim(p.count, c, r);
    for (int k = 0; k < 3; ++k) item.key[k] = 0.5 * (item.box.lo[k] + item.box.hi[k]);
    item.key[3] = 2.0 * item.rmax;
  });
  for (const Impl::BuildItem& item : items) {
    impl_->bounds.add(Vec3(item.box.lo.array() - item.rmax));
    impl_->bounds.add(Vec3(item.box.hi.array() + item.rmax));
  }
  std::vector<Index> order(np);
  std::iota(order.begin(), order.end(), Index{0});
  if (np > 0) {
    impl_->nodes.resize(2 * np - 1);
    impl_->build(0, order, items, 0, static_cast<std::uint32_t>(np));
  }
  impl_->public_index = order;
  impl_->bvh_index.resize(np);
  for (std::size_t i = 0; i < np; ++i) impl_->bvh_index[order[i]] = static_cast<Index>(i);
  std::vector<PrimGeom> sorted(np);
  tbb::parallel_for(std::size_t{0}, np, [&](std::size_t i) { sorted[i] = geometry[order[i]]; });
  geometry = std::move(sorted);
}

Envelope::~Envelope() = default;
Envelope::Envelope(Envelope&&) noexcept = default;
Envelope& Envelope::operator=(Envelope&&) noexcept = default;

const std::vector<EnvelopePrimitive>& Envelope::primitives() const { return impl_->primitives; }

std::pair<Vec3, Vec3> Envelope::bounds() const { return {impl_->bounds.lo, impl_->bounds.hi}; }

double Envelope::signed_distance(const Vec3& x) const { return impl_->query(x).d; }

EnvelopeHit Envelope::closest(const Vec3& x) const {
  const Impl::Hit h = impl_->query(x);
  EnvelopeHit hit;
  hit.distance = h.d;
  if (h.prim >= 0) {
    const Eval e = impl_->ball(x, h.prim);
    hit.centre = e.c;
    hit.radius = e.r;
    hit.primitive = impl_->public_index[static_cast<std::size_t>(h.prim)];
  }
  return hit;
}

std::vector<double> Envelope::signed_distances(const std::vector<Vec3>& points) const {
  std::vector<double> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { out[i] = signed_distance(points[i]); });
  return out;
}

double Envelope::signed_distance_brute_force(const Vec3& x) const {
  double best = kInf;
  for (const PrimGeom& g : impl_->geometry) best = std::min(best, g.eval<false>(x, nullptr));
  return best;
}

double sphere_signed_distance(const Vec3& x, const Vec3& c, double r) { return sphere_value(x, c, r); }
double cone_signed_distance(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1) {
  return make_prim(2, {c0, c1, c1}, {r0, r1, r1}).eval<false>(x, nullptr);
}
double slab_signed_distance(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1, const Vec3& c2,
                            double r2) {
  return make_prim(3, {c0, c1, c2}, {r0, r1, r2}).eval<false>(x, nullptr);
}

// ---- boundary sampling -------------------------------------------------------------------

namespace {

constexpr int kKeyBits = 21;
constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << kKeyBits) - 1;
inline std::uint64_t pack(std::uint64_t i, std::uint64_t j, std::uint64_t k) {
  return (i << (2 * kKeyBits)) | (j << kKeyBits) | k;
}
inline std::array<std::uint64_t, 3> unpack(std::uint64_t key) {
  return {key >> (2 * kKeyBits), (key >> kKeyBits) & kKeyMask, key & kKeyMask};
}

/// A fixed, generic rotation (no axis close to a coordinate axis or plane).
Eigen::Matrix3d grid_rotation() {
  return Eigen::AngleAxisd(0.9, Vec3(1.0, std::sqrt(2.0), std::sqrt(3.0)).normalized()).toRotationMatrix();
}

struct Cell {
  std::uint32_t i, j, k;
  std::int64_t hint;  ///< a primitive near the parent cell's centre, −1 if none
};

}  // namespace

EnvelopeSamples Envelope::sample_boundary(double step, const std::function<void(double)>& progress) const {
  if (!(step > 0) || !std::isfinite(step)) throw std::invalid_argument("envelope sampling: the step must be > 0");
  EnvelopeSamples out;
  out.step = step;
  if (empty()) return out;
  const auto report = [&](double f) {
    if (progress) progress(f);
  };
  const Impl& impl = *impl_;
  using Hit = Impl::Hit;

  // The grid is turned by a fixed generic rotation: a grid aligned with the coordinate axes
  // would alias with axis-aligned shapes (every cross-section of an axis-aligned cylinder meets
  // the grid lines the same way, so the area estimate's errors add up instead of averaging).
  const Eigen::Matrix3d rotation = grid_rotation();  // grid frame -> world
  Box grid_bounds;
  for (const PrimGeom& g : impl.geometry)
    for (int k = 0; k < g.count; ++k) {
      const Vec3 c = rotation.transpose() * g.c[k];
      grid_bounds.add(Vec3(c.array() - g.r[k]));
      grid_bounds.add(Vec3(c.array() + g.r[k]));
    }
  const Vec3 origin = grid_bounds.lo - Vec3::Constant(step);
  const Vec3 extent = grid_bounds.hi - grid_bounds.lo + Vec3::Constant(2 * step);
  const double cells_max = std::ceil(extent.maxCoeff() / step);
  if (cells_max >= static_cast<double>(std::uint64_t{1} << (kKeyBits - 1)))
    throw std::invalid_argument("envelope sampling: the step " + std::to_string(step) +
                                " is too small for an envelope of size " + std::to_string(extent.maxCoeff()));
  int levels = 0;
  while (static_cast<double>(std::uint64_t{1} << levels) < cells_max) ++levels;
  const double scale = extent.norm();
  const double slack = 1e-9 * scale;  // rounding in φ, which is 1-Lipschitz in exact arithmetic
  const auto point = [&](std::uint64_t i, std::uint64_t j, std::uint64_t k) {
    return Vec3(rotation * (origin + step * Vec3(double(i), double(j), double(k))));
  };

  // 1. Octree refinement down to cells of 4×4×4 grid steps (level kLastLevel): keep a cell when
  //    its centre (a grid point) is within half a diagonal of ∂E, as φ is 1-Lipschitz. The values
  //    found that settle a grid point's sign are kept for step 2.
  std::vector<Cell> cells{{0, 0, 0, -1}};
  std::vector<std::pair<std::uint64_t, Hit>> known;
  for (int level = levels; level >= kLastLevel; --level) {
    const std::uint32_t size = std::uint32_t{1} << level, half = size / 2;
    const double half_diagonal = 0.5 * std::sqrt(3.0) * size * step + slack;
    std::vector<Hit> hits(cells.size());
    tbb::parallel_for(std::size_t{0}, cells.size(), [&](std::size_t c) {
      const Cell& cell = cells[c];
      // Only the class matters: φ > h (nothing found below h), φ < −h, or between. The parent's
      // primitive often settles it at once.
      const Vec3 centre = point(cell.i + half, cell.j + half, cell.k + half);
      Hit start{kInf, -1};
      if (cell.hint >= 0)
        start = {impl.geometry[static_cast<std::size_t>(cell.hint)].eval<false>(centre, nullptr), cell.hint};
      hits[c] = impl.query(centre, half_diagonal * (1 + 1e-9), -half_diagonal, half_diagonal, start);
    });
    std::vector<Cell> next;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      // Reusable as a corner value: inside (sign), or outside by more than a step (nothing to
      // locate from it). A kept cell's positive value is only an upper bound.
      if (hits[c].d < 0 || hits[c].prim < 0)
        known.push_back({pack(cells[c].i + half, cells[c].j + half, cells[c].k + half), hits[c]});
      if (hits[c].prim < 0 || hits[c].d < -half_diagonal) continue;
      for (std::uint32_t a = 0; a < 8; ++a)
        next.push_back({cells[c].i + ((a & 1) ? half : 0), cells[c].j + ((a & 2) ? half : 0),
                        cells[c].k + ((a & 4) ? half : 0), hits[c].prim});
    }
    cells = std::move(next);
    report(0.4 * (levels - level + 1) / levels);
  }
  std::sort(known.begin(), known.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (int level = kLastLevel - 1; level >= 1; --level) {
    const std::uint32_t half = std::uint32_t{1} << (level - 1);
    std::vector<Cell> next;
    next.reserve(8 * cells.size());
    for (const Cell& c : cells)
      for (std::uint32_t a = 0; a < 8; ++a)
        next.push_back({c.i + ((a & 1) ? half : 0), c.j + ((a & 2) ? half : 0), c.k + ((a & 4) ? half : 0), c.hint});
    cells = std::move(next);
  }

  // 2. φ at the grid points of the kept cells. Only what a crossing edge needs is computed: the
  //    sign, and for an outside point next to a crossing (so within one step of E) the exact
  //    value and primitive. A search stops at the first primitive containing the point and
  //    ignores anything farther than its reach.
  std::vector<std::uint64_t> corners;
  corners.reserve(8 * cells.size());
  for (const Cell& c : cells)
    for (std::uint32_t a = 0; a < 8; ++a) corners.push_back(pack(c.i + (a & 1), c.j + ((a >> 1) & 1), c.k + ((a >> 2) & 1)));
  tbb::parallel_sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  cells = {};
  //    Coarse-to-fine passes over the lattices L_p (coordinates multiples of 2^p): pass p takes
  //    the points of L_p not in L_{p+1}. Their values are exact up to a reach large enough for
  //    a far value to settle (1-Lipschitz) the points of the next pass around it without a
  //    search. A point of a later pass also tries the primitives found at its neighbours on
  //    L_{p+1}: one that contains it settles its sign, and the smallest value seeds the search.
  std::vector<Hit> values(corners.size());
  const double reach = step * (1 + 1e-9) + slack;
  const auto lattice = [](std::uint64_t key) {
    const auto [i, j, k] = unpack(key);
    const std::uint64_t bits = i | j | k;
    int p = 0;
    while (p < kLastLevel && !((bits >> p) & 1)) ++p;
    return p;
  };
  for (int pass = kLastLevel; pass >= 0; --pass) {
    const double stride = double(std::uint64_t{1} << pass);
    const double pass_reach =
        pass == 0 ? reach : (step + 0.5 * stride * std::sqrt(3.0) * step) * (1 + 1e-9) + slack;
    tbb::parallel_for(std::size_t{0}, corners.size(), [&](std::size_t c) {
      if (lattice(corners[c]) != pass) return;
      const auto it = std::lower_bound(known.begin(), known.end(), corners[c],
                                       [](const auto& entry, std::uint64_t key) { return entry.first < key; });
      if (it != known.end() && it->first == corners[c]) {
        values[c] = it->second;
        return;
      }
      const auto [i, j, k] = unpack(corners[c]);
      const Vec3 z = point(i, j, k);
      Hit start{kInf, -1};
      if (pass < kLastLevel) {
        // Parents: round each coordinate off L_{pass+1} down or up.
        const std::uint64_t s = std::uint64_t{1} << pass, m = 2 * s;
        const bool oi = i % m, oj = j % m, ok = k % m;
        const double offset = s * step * std::sqrt(double(oi + oj + ok));
        std::int64_t tried[8];
        int ntried = 0;
        for (std::uint32_t a = 0; a < 8; ++a) {
          if (((a & 1) && !oi) || ((a & 2) && !oj) || ((a & 4) && !ok)) continue;
          const std::uint64_t key = pack(oi ? i - s + ((a & 1) ? m : 0) : i, oj ? j - s + ((a & 2) ? m : 0) : j,
                                         ok ? k - s + ((a & 4) ? m : 0) : k);
          const auto at = std::lower_bound(corners.begin(), corners.end(), key);
          if (at == corners.end() || *at != key) continue;
          const Hit& near = values[static_cast<std::size_t>(at - corners.begin())];
          if (near.d >= pass_reach + offset) {  // 1-Lipschitz: φ(z) ≥ φ(near) − offset ≥ reach
            values[c] = Hit{near.d - offset, -1};
            return;
          }
          const std::int64_t prim = near.prim;
          if (prim < 0 || std::find(tried, tried + ntried, prim) != tried + ntried) continue;
          tried[ntried++] = prim;
          const double d = impl.geometry[static_cast<std::size_t>(prim)].eval<false>(z, nullptr);
          if (d < start.d) start = {d, prim};
          if (d < 0) break;
        }
      }
      values[c] = impl.query(z, pass_reach, 0.0, -kInf, start);
    });
  }
  report(0.9);

  // 3. Every grid edge whose ends differ in sign crosses ∂E. Its sample is the closest point of E
  //    to the outside end a (exactly on ∂E: a is outside, so the closest point of the nearest
  //    primitive is the closest point of the union), with outward normal (a − c*)/|a − c*|.
  std::vector<std::array<std::uint64_t, 2>> crossings;  // outside key, inside key
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const auto [i, j, k] = unpack(corners[c]);
    for (int axis = 0; axis < 3; ++axis) {
      const std::uint64_t next = pack(i + (axis == 0), j + (axis == 1), k + (axis == 2));
      const auto it = std::lower_bound(corners.begin(), corners.end(), next);
      if (it == corners.end() || *it != next) continue;
      const std::size_t n = static_cast<std::size_t>(it - corners.begin());
      const bool out_c = values[c].d >= 0, out_n = values[n].d >= 0;
      if (out_c == out_n) continue;
      crossings.push_back(out_c ? std::array<std::uint64_t, 2>{c, n} : std::array<std::uint64_t, 2>{n, c});
    }
  }
  out.points.resize(crossings.size());
  out.normals.resize(crossings.size());
  out.primitives.resize(crossings.size());
  out.areas.resize(crossings.size());
  tbb::parallel_for(std::size_t{0}, crossings.size(), [&](std::size_t e) {
    const std::size_t a = crossings[e][0], b = crossings[e][1];
    const auto [ai, aj, ak] = unpack(corners[a]);
    const auto [bi, bj, bk] = unpack(corners[b]);
    const Vec3 pa = point(ai, aj, ak), pb = point(bi, bj, bk);
    Hit hit = values[a];
    if (hit.prim < 0) hit = impl.query(pa);  // not expected: an outside end is within a step of E
    const Eval ball = impl.ball(pa, hit.prim);
    Vec3 n = pa - ball.c;
    const double len = n.norm();
    n = len > 1e-12 * scale ? Vec3(n / len) : Vec3((pa - pb).normalized());
    out.points[e] = hit.d > 0 ? Vec3(ball.c + ball.r * n) : pa;
    out.normals[e] = n;
    out.primitives[e] = impl.public_index[static_cast<std::size_t>(hit.prim)];
    out.areas[e] = step * step / (rotation.transpose() * n).lpNorm<1>();
  });
  report(1.0);
  return out;
}

std::vector<double> Envelope::boundary_distances(const std::vector<Vec3>& points, const EnvelopeSamples& samples,
                                                 std::vector<double>* signed_distances_out) const {
  std::vector<double> out(points.size());
  if (signed_distances_out) signed_distances_out->assign(points.size(), kInf);
  if (empty()) {
    std::fill(out.begin(), out.end(), kInf);
    return out;
  }
  // Inside E the depth D into the union satisfies −φ(x) ≤ D. The closest point q of ∂P for the
  // deepest primitive P is at distance −φ(x); when no other primitive covers q, q is on ∂E and
  // D = −φ(x) exactly. Otherwise D ≤ the distance to the nearest boundary sample.
  const auto [lo, hi] = bounds();
  const double tolerance = 1e-9 * (hi - lo).norm();
  std::unique_ptr<PointIndex> index;
  if (!samples.points.empty()) index = std::make_unique<PointIndex>(samples.points);
  const bool hints = index && samples.primitives.size() == samples.points.size();
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    const Vec3& x = points[i];
    // The primitive under the nearest boundary sample seeds the search.
    Impl::Hit start{kInf, -1};
    if (hints) {
      const Index p = samples.primitives[index->nearest(x).first];
      if (p < impl_->bvh_index.size()) {
        const std::int64_t b = impl_->bvh_index[p];
        start = {impl_->geometry[static_cast<std::size_t>(b)].eval<false>(x, nullptr), b};
      }
    }
    const Impl::Hit hit = impl_->query(x, kInf, -kInf, -kInf, start);
    if (signed_distances_out) (*signed_distances_out)[i] = hit.d;
    if (hit.d >= 0) {
      out[i] = hit.d;
      return;
    }
    const double depth = -hit.d;
    const Eval ball = impl_->ball(x, hit.prim);
    const Vec3 away = x - ball.c;
    const double len = away.norm();
    if (len > 0 || ball.r == 0) {
      const Vec3 q = len > 0 ? Vec3(ball.c + ball.r * away / len) : ball.c;
      if (impl_->query(q, tolerance, -tolerance, tolerance, {0.0, hit.prim}).d >= -tolerance) {
        out[i] = depth;
        return;
      }
    }
    out[i] = index ? std::max(depth, index->nearest(x).second) : depth;
  });
  return out;
}

}  // namespace medax::services
