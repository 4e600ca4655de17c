#pragma once
// Internal to the envelope service: the closed-form signed distances of its primitives (a
// sphere, a medial cone, a medial slab; see medax/services/envelope.hpp). Inline, as the BVH
// search and the boundary sampling evaluate them in their innermost loops.
#include <medax/geometry.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace medax::services::envelope_detail {

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
  double q = 0;         ///< √(1 − k²); 0 when one ball contains the other (|k| ≥ 1) or c0 = c1
  Vec3 u = Vec3::Zero();  ///< the unit axis (c1 − c0)/L, when q > 0

  ConeFrame() = default;
  ConeFrame(const Vec3& c0, double r0, const Vec3& c1, double r1) {
    length = (c1 - c0).norm();
    if (!(length > 0)) return;
    inv_length = 1 / length;
    k = (r1 - r0) / length;
    if (!(std::abs(k) < 1)) return;
    q = std::sqrt(1 - k * k);
    u = (c1 - c0) * inv_length;
  }
};

// min over t of |x − c(t)| − r(t) along a cone. With s the axial coordinate of x from c0, ρ its
// distance to the axis and k = (r1 − r0)/L the slope, the objective sqrt((s − t)² + ρ²) − r0 − k·t
// is convex in t; its stationary point is t* = s + kρ/√(1−k²), where it equals
// ρ√(1−k²) − r0 − k·s. When t* leaves [0, L] (or |k| ≥ 1) the minimum is at an end ball.
template <bool kFull>
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline double cone_value(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1, const ConeFrame& f,
                         Eval* out) {
  const Vec3 w = x - c0;
  if (f.q > 0) {
    const Vec3& u = f.u;
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

/// Geometry of one primitive: its balls (the first `count` are used) and the frames of its
/// closed forms.
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

  /// sd_P(x); with kFull, also the interpolated ball realising it, in *out.
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
    // The sides in order (0, 1), (1, 2), (2, 0), the first of equal values kept.
    double best = kInf;
    if (visible[0]) best = side_value<kFull, 0>(x, best, out);
    if (visible[1]) best = side_value<kFull, 1>(x, best, out);
    if (visible[2]) best = side_value<kFull, 2>(x, best, out);
    return best;
  }

  /// min(best, the cone of side k at x); with kFull, *out follows the minimum.
  template <bool kFull, int k>
  double side_value(const Vec3& x, double best, Eval* out) const {
    constexpr int j = (k + 1) % 3;
    Eval e;
    const double d = cone_value<kFull>(x, c[k], r[k], c[j], r[j], edge[k], &e);
    if (!(d < best)) return best;
    if constexpr (kFull) *out = e;
    return d;
  }

  double value(const Vec3& x) const { return eval<false>(x, nullptr); }

  Eval full(const Vec3& x) const {
    Eval e;
    eval<true>(x, &e);
    return e;
  }
};

/// A primitive of `count` balls (c[k], r[k]); unused slots repeat the last ball.
inline PrimGeom make_prim(int count, const std::array<Vec3, 3>& c, const std::array<double, 3>& r) {
  PrimGeom p;
  p.count = count;
  p.c = c;
  p.r = r;
  p.init();
  return p;
}

}  // namespace medax::services::envelope_detail
