#pragma once
// Internal to the envelope service: a bounding-volume hierarchy over the envelope's primitives,
// searched nearest-first for φ(x) = min_P sd_P(x). The search is inline: the boundary sampling
// runs it millions of times.
#include "envelope_primitives.hpp"

#include <array>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cstdint>
#include <vector>

namespace medax::services::envelope_detail {

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
struct BvhNode {
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

/// The two children of an inner node, side by side, as the search reads them: their bounds (the
/// fields of BvhNode, one lane per child, widened to double) and where each leads. Both lower
/// bounds come from one pass of two-lane arithmetic, each lane doing BvhNode::lower_bound's
/// operations in its order, so the bounds are the same doubles.
struct ChildPair {
  enum Row { kLo = 0, kHi = 3, kG = 6, kRmax = 9, kSlope = 10, kGamma = 11, kRows = 12 };
  double lane[kRows][2];  ///< the node's floats, widened once (not at every visit)
  std::uint32_t index[2];  ///< inner child: its pair's index; leaf child: its first primitive
  std::uint32_t count[2];  ///< leaf child: its number of primitives; inner child: 0

  void set(int side, const BvhNode& child, std::uint32_t child_index);
  /// lower_bound(x) of both children.
  void lower_bounds(const Vec3& x, double out[2]) const;
};

/// A value of φ and the primitive giving it.
struct Hit {
  double d;
  std::int64_t prim;  ///< BVH-order index, −1 when nothing below `upper` was found
};

class EnvelopeBvh {
 public:
  EnvelopeBvh() = default;
  /// Builds the hierarchy over `primitives` (given in public order; kept in BVH order).
  explicit EnvelopeBvh(std::vector<PrimGeom> primitives);

  /// The primitives in BVH order.
  const std::vector<PrimGeom>& geometry() const { return geometry_; }
  const PrimGeom& primitive(std::int64_t prim) const { return geometry_[static_cast<std::size_t>(prim)]; }
  /// BVH order -> public order, and back.
  Index public_index(std::int64_t prim) const { return public_index_[static_cast<std::size_t>(prim)]; }
  const std::vector<Index>& bvh_index() const { return bvh_index_; }
  /// Box of every ball.
  const Box& bounds() const { return bounds_; }

  /// min over primitives of sd_P(x). Values ≥ `upper` are not reported (the result is then
  /// {upper, −1}); the search stops as soon as a value below `stop_below` is found (the result is
  /// then an upper bound on φ(x), below stop_below). Once a value ≤ `settle` is found, only the
  /// question "is φ(x) < stop_below?" is pursued (nodes are pruned at stop_below): the result is
  /// then not exact, only φ(x) ∈ [stop_below, result]. `start` (a primitive and its value at x,
  /// e.g. from a neighbouring query) seeds the search.
  Hit query(const Vec3& x, double upper = kInf, double stop_below = -kInf, double settle = -kInf,
            Hit start = {kInf, -1}) const;

  /// The interpolated ball of primitive `prim` (BVH order) realising its value at x.
  Eval ball(const Vec3& x, std::int64_t prim) const { return primitive(prim).full(x); }

 private:
  /// Keeps the root and, per inner node of `nodes` (built left child next, right child at
  /// `first`), its children's pair.
  void pair_children(const std::vector<BvhNode>& nodes);

  std::vector<PrimGeom> geometry_;   // BVH order
  std::vector<Index> public_index_;  // BVH order -> public order
  std::vector<Index> bvh_index_;     // public order -> BVH order
  BvhNode root_;                  // the root's bounds
  std::vector<ChildPair> pairs_;  // the inner nodes' children, root's first; empty when the root is a leaf
  Box bounds_;
};

inline void ChildPair::set(int side, const BvhNode& child, std::uint32_t child_index) {
  for (int k = 0; k < 3; ++k) {
    lane[kLo + k][side] = child.lo[k];
    lane[kHi + k][side] = child.hi[k];
    lane[kG + k][side] = child.g[k];
  }
  lane[kRmax][side] = child.rmax;
  lane[kSlope][side] = child.slope;
  lane[kGamma][side] = child.gamma;
  index[side] = child.count > 0 ? child.first : child_index;
  count[side] = child.count;
}

#if defined(__SSE2__)
inline void ChildPair::lower_bounds(const Vec3& x, double out[2]) const {
  const auto row = [this](int r) { return _mm_loadu_pd(lane[r]); };
  const __m128d zero = _mm_setzero_pd();
  __m128d d2 = zero, gx = zero;
  for (int k = 0; k < 3; ++k) {
    const __m128d xk = _mm_set1_pd(x[k]);
    const __m128d below = _mm_sub_pd(row(kLo + k), xk), above = _mm_sub_pd(xk, row(kHi + k));
    // std::max(0, std::max(below, above)) lane by lane (no NaN here).
    const __m128d o = _mm_max_pd(_mm_max_pd(above, below), zero);
    d2 = _mm_add_pd(d2, _mm_mul_pd(o, o));
    gx = _mm_add_pd(gx, _mm_mul_pd(row(kG + k), xk));
  }
  const __m128d d = _mm_sqrt_pd(d2);
  const __m128d by_radius = _mm_sub_pd(d, row(kRmax));
  const __m128d by_slope =
      _mm_add_pd(_mm_sub_pd(_mm_mul_pd(_mm_sub_pd(_mm_set1_pd(1.0), row(kSlope)), d), gx), row(kGamma));
  _mm_storeu_pd(out, _mm_max_pd(by_slope, by_radius));
}
#else
inline void ChildPair::lower_bounds(const Vec3& x, double out[2]) const {
  for (int side = 0; side < 2; ++side) {
    BvhNode node;
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = lane[kLo + k][side];
      node.hi[k] = lane[kHi + k][side];
      node.g[k] = lane[kG + k][side];
    }
    node.rmax = lane[kRmax][side];
    node.slope = lane[kSlope][side];
    node.gamma = lane[kGamma][side];
    out[side] = node.lower_bound(x);
  }
}
#endif

inline Hit EnvelopeBvh::query(const Vec3& x, double upper, double stop_below, double settle, Hit start) const {
  Hit best = start.prim >= 0 && start.d < upper ? start : Hit{upper, -1};
  if (best.d < stop_below) return best;
  double bound = best.prim >= 0 && best.d <= settle ? stop_below : best.d;  // prune what cannot go below
  if (geometry_.empty()) return best;
  // A node to visit: an inner node's pair (count 0) or a leaf's primitives, and its lower bound.
  struct Item {
    std::uint32_t index, count;
    double lb;
  };
  Item stack[128];
  int top = 0;
  const double lb_root = root_.lower_bound(x);
  if (lb_root < bound) stack[top++] = {root_.count > 0 ? root_.first : 0, root_.count, lb_root};
  while (top > 0) {
    const Item item = stack[--top];
    if (item.lb >= bound) continue;
    if (item.count > 0) {
      for (std::uint32_t i = item.index; i < item.index + item.count; ++i) {
        const double d = geometry_[i].value(x);
        if (d < best.d) {
          best = {d, static_cast<std::int64_t>(i)};
          if (best.d < stop_below) return best;
          bound = best.d <= settle ? stop_below : best.d;
        }
      }
      continue;
    }
    const ChildPair& pair = pairs_[item.index];
    double lb[2];
    pair.lower_bounds(x, lb);
    const Item left{pair.index[0], pair.count[0], lb[0]}, right{pair.index[1], pair.count[1], lb[1]};
    // Push the farther child first so that the nearer one is explored first.
    if (lb[0] <= lb[1]) {
      if (lb[1] < bound) stack[top++] = right;
      if (lb[0] < bound) stack[top++] = left;
    } else {
      if (lb[0] < bound) stack[top++] = left;
      if (lb[1] < bound) stack[top++] = right;
    }
  }
  return best;
}

}  // namespace medax::services::envelope_detail
