#pragma once
// Spheres and spherical quadrics (SQEM, Thiery et al. 2013) as VMAS uses them (notes §2.1).
// A sphere is s = (q, r) ∈ R⁴; the squared distance from a sphere to the plane {p, n}⊥ is
//     Q_{p,n}(s) = (n·(p − q) − r)² = ½ sᵀ A s − bᵀ s + c,
//     A = 2 ñ ñᵀ, b = 2 (n·p) ñ, c = (n·p)², ñ = (n, 1).
// Quadrics add component-wise, so a vertex's diffused quadric and a cluster's sum are quadrics.
#include <medax/geometry.hpp>

#include <array>

namespace medax::vmas {

using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

struct Sphere {
  Vec3 centre = Vec3::Zero();
  double radius = 0;
  Vec4 s() const { return {centre.x(), centre.y(), centre.z(), radius}; }
  static Sphere from(const Vec4& s) { return {s.head<3>(), s[3]}; }
};

struct Quadric {
  Mat4 A = Mat4::Zero();
  Vec4 b = Vec4::Zero();
  double c = 0;

  /// w · (n·(p − q) − r)².
  static Quadric plane(const Vec3& p, const Vec3& n, double w) {
    const Vec4 nt(n.x(), n.y(), n.z(), 1.0);
    const double np = n.dot(p);
    return {2 * w * nt * nt.transpose(), 2 * w * np * nt, w * np * np};
  }
  /// (β − a·s)²: one linear residual row squared.
  static Quadric row(const Vec4& a, double beta) { return {2 * a * a.transpose(), 2 * beta * a, beta * beta}; }

  double operator()(const Vec4& s) const { return 0.5 * s.dot(A * s) - b.dot(s) + c; }
  Quadric& operator+=(const Quadric& o) {
    A += o.A;
    b += o.b;
    c += o.c;
    return *this;
  }
};

/// A quadric packed for fast evaluation against many spheres: Q(s) = k·m(s) + c where
/// m(s) = (s0², s1², s2², s3², s0s1, s0s2, s0s3, s1s2, s1s3, s2s3, s0, s1, s2, s3).
struct PackedQuadric {
  std::array<double, 14> k{};
  double c = 0;

  static PackedQuadric from(const Quadric& q) {
    PackedQuadric p;
    p.k = {0.5 * q.A(0, 0), 0.5 * q.A(1, 1), 0.5 * q.A(2, 2), 0.5 * q.A(3, 3), q.A(0, 1), q.A(0, 2), q.A(0, 3),
           q.A(1, 2),       q.A(1, 3),       q.A(2, 3),       -q.b[0],         -q.b[1],  -q.b[2],  -q.b[3]};
    p.c = q.c;
    return p;
  }
  Quadric unpack() const {
    Quadric q;
    for (int i = 0; i < 4; ++i) q.A(i, i) = 2 * k[i];
    q.A(0, 1) = q.A(1, 0) = k[4];
    q.A(0, 2) = q.A(2, 0) = k[5];
    q.A(0, 3) = q.A(3, 0) = k[6];
    q.A(1, 2) = q.A(2, 1) = k[7];
    q.A(1, 3) = q.A(3, 1) = k[8];
    q.A(2, 3) = q.A(3, 2) = k[9];
    for (int i = 0; i < 4; ++i) q.b[i] = -k[10 + i];
    q.c = c;
    return q;
  }
};

/// The monomials m(s) of a sphere, computed once per sphere and partition.
inline std::array<double, 14> monomials(const Sphere& sp) {
  const double s0 = sp.centre.x(), s1 = sp.centre.y(), s2 = sp.centre.z(), s3 = sp.radius;
  return {s0 * s0, s1 * s1, s2 * s2, s3 * s3, s0 * s1, s0 * s2, s0 * s3, s1 * s2, s1 * s3, s2 * s3, s0, s1, s2, s3};
}

}  // namespace medax::vmas
