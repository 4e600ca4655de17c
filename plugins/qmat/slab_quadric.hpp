#pragma once
// Q-MAT's slab quadric error metric (SQEM, notes qmat_coverage_axis.md §1.2–1.3, §1.5).
//
// A sphere is s = (c, r) ∈ R⁴. A plane with unit normal n at offset n·p gives the signed
// distance d = n·p − ñ·s of the sphere's tangent point, ñ = (n, 1); its quadric is
// Q(s) = d² = ½ sᵀAs − bᵀs + c₀ with A = 2ññᵀ, b = 2(n·p)ñ, c₀ = (n·p)², and quadrics add.
// All of it works in normalised units (coordinates and radii divided by a unit length), where
// the authors' thresholds live.
#include <medax/geometry.hpp>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <optional>

namespace medax::qmat {

using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

/// A sphere (centre, radius) as one vector.
inline Vec4 sphere4(const Vec3& c, double r) { return {c.x(), c.y(), c.z(), r}; }
inline Vec3 centre_of(const Vec4& s) { return s.head<3>(); }

struct SlabQuadric {
  Mat4 A = Mat4::Zero();
  Vec4 b = Vec4::Zero();
  double c = 0;

  /// The plane with normal `n` (unit in the paper; see cone terms) tangent to sphere `at`,
  /// times `weight`: it vanishes at `at`.
  static SlabQuadric tangent_plane(const Vec3& n, const Vec4& at, double weight = 1);

  double operator()(const Vec4& s) const { return 0.5 * s.dot(A * s) - b.dot(s) + c; }
  SlabQuadric& operator+=(const SlabQuadric& o) {
    A += o.A;
    b += o.b;
    c += o.c;
    return *this;
  }
  friend SlabQuadric operator+(SlabQuadric a, const SlabQuadric& o) { return a += o; }
  bool is_zero() const { return (A.array() == 0).all() && (b.array() == 0).all() && c == 0; }
  /// Whether |det A| > `singular` (the authors' test, 1e-12, for a usable minimiser).
  bool invertible(double singular) const { return std::abs(A.determinant()) > singular; }
  /// The solution of A m = b when it is finite; call only when A is invertible.
  std::optional<Vec4> solution() const;
  /// The minimiser (A m = b), or nothing when |det A| ≤ `singular`.
  std::optional<Vec4> minimiser(double singular) const {
    return invertible(singular) ? solution() : std::nullopt;
  }
};

/// A slab quadric whose A is symmetric bit for bit, stored as the upper triangle of A, b and c:
/// 128 bytes (two cache lines) instead of 176, for the vertex quadrics the collapse loop reads
/// at random. Every slab plane has weight 1, so A's entries (2ñᵣ)·ñ꜀ and (2ñ꜀)·ñᵣ are the same
/// rounded product (doubling is exact), and sums of symmetric matrices stay symmetric; unpacking
/// gives back the very same bits.
struct alignas(64) PackedQuadric {
  std::array<double, 10> upper{};  ///< A(r, c) for r ≤ c, row by row
  std::array<double, 4> b{};
  double c = 0;

  /// Packs q; throws std::logic_error when q.A is not exactly symmetric.
  static PackedQuadric pack(const SlabQuadric& q);
  /// The full quadric of this + o: the same bits as adding the full quadrics (inline: the
  /// collapse calls it once per edge costed).
  SlabQuadric plus(const PackedQuadric& o) const;
  PackedQuadric& operator+=(const PackedQuadric& o);
};

inline SlabQuadric PackedQuadric::plus(const PackedQuadric& o) const {
  constexpr int kRow[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3}, kCol[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};
  SlabQuadric q;
  for (int k = 0; k < 10; ++k) q.A(kRow[k], kCol[k]) = q.A(kCol[k], kRow[k]) = upper[k] + o.upper[k];
  for (int r = 0; r < 4; ++r) q.b[r] = b[r] + o.b[r];
  q.c = c + o.c;
  return q;
}

/// x with A x = b by partial-pivot LU, bit for bit what Eigen's A.partialPivLu().solve(b)
/// gives (Eigen 3.4, no FMA), at a fraction of its cost: the collapse solves one per edge costed.
Vec4 solve_partial_pivot(const Mat4& A, Vec4 b);

/// The two tangent planes of the slab of three spheres: unit n with n·(cᵢ − c₀) = r₀ − rᵢ.
/// Nothing when two centres are closer than `min_distance` (1e-8), the centres are collinear, or
/// no such plane exists (one sphere swallows the slab).
std::optional<std::array<Vec3, 2>> slab_normals(const Vec4& m0, const Vec4& m1, const Vec4& m2,
                                                double min_distance = 1e-8);

/// The stability ratio γ = max(0, ‖cᵢ − cⱼ‖ − |rᵢ − rⱼ|) / ‖cᵢ − cⱼ‖, 0 when the centres coincide
/// (§1.5). In [0, 1]; 1 for equal radii; 0 iff one sphere contains the other.
double stability_ratio(const Vec4& mi, const Vec4& mj);

}  // namespace medax::qmat
