#pragma once
// Internal to the envelope service: a bounding-volume hierarchy over the envelope's primitives,
// searched nearest-first for φ(x) = min_P sd_P(x). The search is inline: the boundary sampling
// runs it millions of times.
#include "envelope_primitives.hpp"

#include <array>
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
  std::vector<PrimGeom> geometry_;   // BVH order
  std::vector<Index> public_index_;  // BVH order -> public order
  std::vector<Index> bvh_index_;     // public order -> BVH order
  std::vector<BvhNode> nodes_;
  Box bounds_;
};

inline Hit EnvelopeBvh::query(const Vec3& x, double upper, double stop_below, double settle, Hit start) const {
  Hit best = start.prim >= 0 && start.d < upper ? start : Hit{upper, -1};
  if (best.d < stop_below) return best;
  double bound = best.prim >= 0 && best.d <= settle ? stop_below : best.d;  // prune what cannot go below
  if (nodes_.empty()) return best;
  struct Item {
    std::uint32_t node;
    double lb;
  };
  Item stack[128];
  int top = 0;
  const double lb_root = nodes_[0].lower_bound(x);
  if (lb_root < bound) stack[top++] = {0, lb_root};
  while (top > 0) {
    const Item item = stack[--top];
    if (item.lb >= bound) continue;
    const BvhNode& node = nodes_[item.node];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const double d = geometry_[i].value(x);
        if (d < best.d) {
          best = {d, static_cast<std::int64_t>(i)};
          if (best.d < stop_below) return best;
          bound = best.d <= settle ? stop_below : best.d;
        }
      }
      continue;
    }
    const std::uint32_t left = item.node + 1, right = node.first;
    const double lb_left = nodes_[left].lower_bound(x), lb_right = nodes_[right].lower_bound(x);
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

}  // namespace medax::services::envelope_detail
