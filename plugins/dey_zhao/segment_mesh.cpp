#include "segment_mesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace medax::dey_zhao {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

constexpr std::uint32_t kLeafSize = 2;

double max_abs(const Vec3& p) { return p.cwiseAbs().maxCoeff(); }

/// The margin that keeps the slab test conservative for coordinates up to `extent` (below).
double slab_margin(double extent) { return std::ldexp(extent, -40); }

/// The segment prepared for the slab test against the boxes. Conservative: a box that the
/// exact segment meets is never rejected. Each computed slab parameter (lo − a)·(1/d) is within
/// 13u·E/|d| of the exact one (u = 2^-53, E the largest |coordinate| of box and segment), so
/// boxes widened by slab_margin(E) = 2^-40·E > 13u·E keep the exact meeting parameter inside the
/// computed interval. The stored boxes are widened by slab_margin(mesh extent); a segment
/// reaching farther out widens them again by its own margin, in the general path, which also
/// tests an axis along which d is 0 (or 1/d overflows) by its range.
struct SegmentSlabs {
  std::array<double, 3> a, inv, lo, hi;
  bool general = false;  ///< an axis tested by its range, or a margin to add
  double margin = 0;     ///< added to the stored boxes' widening (general path)
#if defined(__SSE2__)
  __m128d a2[3], inv2[3];  ///< a and inv in both lanes
#endif

  SegmentSlabs(const Vec3& from, const Vec3& to, double mesh_extent) {
    const double extent = std::max(max_abs(from), max_abs(to));
    if (extent > mesh_extent) general = true, margin = slab_margin(extent);
    for (int i = 0; i < 3; ++i) {
      a[i] = from[i];
      inv[i] = 1.0 / (to[i] - from[i]);
      general = general || !std::isfinite(inv[i]);
      lo[i] = std::min(from[i], to[i]);
      hi[i] = std::max(from[i], to[i]);
#if defined(__SSE2__)
      a2[i] = _mm_set1_pd(a[i]), inv2[i] = _mm_set1_pd(inv[i]);
#endif
    }
  }

  /// Whether the segment may meet the box of the node's child `k`.
  template <typename Node>
  bool may_meet(const Node& n, int k) const {
    double t0 = 0, t1 = 1;
    for (int i = 0; i < 3; ++i) {
      const double l = n.lo[i][k] - margin, h = n.hi[i][k] + margin;
      if (!std::isfinite(inv[i])) {
        if (hi[i] < l || lo[i] > h) return false;
        continue;
      }
      const double u = (l - a[i]) * inv[i], v = (h - a[i]) * inv[i];
      t0 = std::max(t0, std::min(u, v));
      t1 = std::min(t1, std::max(u, v));
    }
    return t0 <= t1;
  }

  /// Bit k: the segment may meet the box of the node's child k. Two lanes at a time (each lane
  /// the operations of may_meet with margin 0) unless general.
  template <typename Node>
  int may_meet_children(const Node& n) const {
#if defined(__SSE2__)
    if (!general) {
      int hits = 0;
      for (int half = 0; half < 4; half += 2) {
        __m128d t0 = _mm_setzero_pd(), t1 = _mm_set1_pd(1.0);
        for (int i = 0; i < 3; ++i) {
          const __m128d u = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(n.lo[i] + half), a2[i]), inv2[i]);
          const __m128d v = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(n.hi[i] + half), a2[i]), inv2[i]);
          t0 = _mm_max_pd(t0, _mm_min_pd(u, v));
          t1 = _mm_min_pd(t1, _mm_max_pd(u, v));
        }
        hits |= _mm_movemask_pd(_mm_cmple_pd(t0, t1)) << half;
      }
      return hits & n.slots;
    }
#endif
    int hits = 0;
    for (int k = 0; k < 4; ++k)
      if ((n.slots >> k) & 1) hits |= static_cast<int>(may_meet(n, k)) << k;
    return hits;
  }
};

/// Certified sign of orientation(t0, t1, t2, x) = det[t1 − t0, t2 − t0, x − t0] from the
/// triangle's stored minors, 0 when not certain. The evaluation is Shewchuk's orient3d
/// (Adaptive Precision Floating-Point Arithmetic, 1997) expanded along x − t0, so his forward
/// error bound errboundA = 7.77e-16 × permanent holds (rounded up to 1e-15); a bound too small
/// to trust (underflow) or a non-finite value gives 0.
int plane_side(const Vec3& t0, const Vec3& normal, const Vec3& magnitude, const Vec3& x) {
  const Vec3 w = x - t0;
  const double det = w.x() * normal.x() + w.y() * normal.y() + w.z() * normal.z();
  const double bound = 1e-15 * (std::abs(w.x()) * magnitude.x() + std::abs(w.y()) * magnitude.y() +
                                std::abs(w.z()) * magnitude.z());
  if (!(bound > 1e-280)) return 0;
  return det > bound ? 1 : -det > bound ? -1 : 0;
}

/// Exact: does the closed segment [a, b] meet the closed triangle t? The two common cases are
/// decided by orientations alone: both ends strictly on one side of t's plane (no), or strictly
/// on both sides, with the line strictly on one side of every edge (yes when all three sides
/// agree). Anything touching (a zero orientation) goes to CGAL's do_intersect.
bool meets_triangle(const std::array<Vec3, 3>& t, const K::Point_3& a, const K::Point_3& b) {
  const K::Point_3 p = point(t[0]), q = point(t[1]), r = point(t[2]);
  const CGAL::Orientation side_a = CGAL::orientation(p, q, r, a), side_b = CGAL::orientation(p, q, r, b);
  if (side_a == side_b && side_a != CGAL::COPLANAR) return false;
  if (side_a != CGAL::COPLANAR && side_b != CGAL::COPLANAR) {
    const CGAL::Orientation e1 = CGAL::orientation(a, b, p, q), e2 = CGAL::orientation(a, b, q, r),
                            e3 = CGAL::orientation(a, b, r, p);
    if (e1 != CGAL::COPLANAR && e2 != CGAL::COPLANAR && e3 != CGAL::COPLANAR) return e1 == e2 && e2 == e3;
  }
  return CGAL::do_intersect(K::Triangle_3(p, q, r), K::Segment_3(a, b));
}

}  // namespace

SegmentMeshTest::SegmentMeshTest(const SurfaceMesh& mesh) {
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.faces.size());
  for (const Tri& f : mesh.faces) {
    const Triangle t{mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]};
    if (!CGAL::collinear(point(t[0]), point(t[1]), point(t[2]))) triangles.push_back(t);
  }
  if (triangles.size() >= std::numeric_limits<std::uint32_t>::max() / 2)
    throw std::invalid_argument("segment test: too many triangles");
  std::vector<Vec3> centroids(triangles.size());
  std::vector<std::uint32_t> order(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    centroids[i] = (triangles[i][0] + triangles[i][1] + triangles[i][2]) / 3;
    order[i] = static_cast<std::uint32_t>(i);
    for (const Vec3& v : triangles[i]) extent_ = std::max(extent_, max_abs(v));
  }
  if (triangles.empty()) return;
  nodes_.reserve(triangles.size() / 2 + 1);
  Box box;
  const Ref root = build(0, static_cast<std::uint32_t>(triangles.size()), order, centroids, triangles, box);
  set_child(top_, 0, root, box);
  triangles_.reserve(triangles.size());
  for (std::uint32_t i : order) triangles_.push_back(triangles[i]);
  planes_.reserve(triangles_.size());
  for (const Triangle& t : triangles_) {
    const Vec3 u = t[1] - t[0], v = t[2] - t[0];
    const Vec3 yz_zx_xy(u.y() * v.z(), u.z() * v.x(), u.x() * v.y()), zy_xz_yx(u.z() * v.y(), u.x() * v.z(), u.y() * v.x());
    planes_.push_back({yz_zx_xy - zy_xz_yx, yz_zx_xy.cwiseAbs() + zy_xz_yx.cwiseAbs()});
  }
}

/// Sorts order[begin, end) around its median along the longest side of the centroids' box (ties
/// by index: deterministic) and returns the median's position.
std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, std::vector<std::uint32_t>& order,
                           const std::vector<Vec3>& centroids) {
  Vec3 centre_lo = centroids[order[begin]], centre_hi = centre_lo;
  for (std::uint32_t k = begin; k < end; ++k)
    centre_lo = centre_lo.cwiseMin(centroids[order[k]]), centre_hi = centre_hi.cwiseMax(centroids[order[k]]);
  int axis = 0;
  (centre_hi - centre_lo).maxCoeff(&axis);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](std::uint32_t x, std::uint32_t y) {
    return centroids[x][axis] != centroids[y][axis] ? centroids[x][axis] < centroids[y][axis] : x < y;
  });
  return mid;
}

SegmentMeshTest::Ref SegmentMeshTest::build(std::uint32_t begin, std::uint32_t end, std::vector<std::uint32_t>& order,
                                            const std::vector<Vec3>& centroids, const std::vector<Triangle>& triangles,
                                            Box& box) {
  if (end - begin <= kLeafSize) {
    box = {triangles[order[begin]][0], triangles[order[begin]][0]};
    for (std::uint32_t k = begin; k < end; ++k)
      for (const Vec3& v : triangles[order[k]]) box.lo = box.lo.cwiseMin(v), box.hi = box.hi.cwiseMax(v);
    return {begin, end - begin};
  }
  // The ranges of the up to four children: each half split again when it is not a leaf.
  std::vector<std::uint32_t> cuts{begin};
  const std::uint32_t mid = median_split(begin, end, order, centroids);
  for (const auto [from, to] : {std::pair{begin, mid}, std::pair{mid, end}}) {
    if (to - from > kLeafSize) cuts.push_back(median_split(from, to, order, centroids));
    cuts.push_back(to);
  }
  const auto node = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  box = {Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    Box child_box;
    const Ref child = build(cuts[k], cuts[k + 1], order, centroids, triangles, child_box);
    set_child(nodes_[node], static_cast<int>(k), child, child_box);
    box = {box.lo.cwiseMin(child_box.lo), box.hi.cwiseMax(child_box.hi)};
  }
  return {node, 0};
}

void SegmentMeshTest::set_child(Node& n, int k, Ref child, const Box& box) const {
  const double margin = slab_margin(extent_);
  n.child[k] = child;
  n.slots |= 1 << k;
  for (int i = 0; i < 3; ++i) n.lo[i][k] = box.lo[i] - margin, n.hi[i][k] = box.hi[i] + margin;
}

bool SegmentMeshTest::leaf_meets(Ref leaf, const Vec3& a, const Vec3& b) const {
  for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k) {
    const Plane& plane = planes_[k];
    const int side_a = plane_side(triangles_[k][0], plane.normal, plane.magnitude, a);
    if (side_a != 0 && side_a == plane_side(triangles_[k][0], plane.normal, plane.magnitude, b)) continue;
    if (meets_triangle(triangles_[k], point(a), point(b))) return true;
  }
  return false;
}

bool SegmentMeshTest::meets(const Vec3& a, const Vec3& b) const {
  if (triangles_.empty()) return false;
  const SegmentSlabs slabs(a, b, extent_);
  if (!slabs.may_meet(top_, 0)) return false;
  Ref stack[64];  // median splits are balanced: depth ≤ log4(triangles) + 1, up to 3 waiting per level
  int top = 0;
  stack[top++] = top_.child[0];
  while (top > 0) {
    const Ref r = stack[--top];
    if (r.count > 0) {
      if (leaf_meets(r, a, b)) return true;
      continue;
    }
    const Node& n = nodes_[r.first];
    const int hits = slabs.may_meet_children(n);
    for (int k = 0; k < 4; ++k)
      if ((hits >> k) & 1) stack[top++] = n.child[k];
  }
  return false;
}

}  // namespace medax::dey_zhao
