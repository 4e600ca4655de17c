#include "slab_quadric.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace medax::qmat {

SlabQuadric SlabQuadric::tangent_plane(const Vec3& n, const Vec4& at, double weight) {
  const Vec4 nt(n.x(), n.y(), n.z(), 1.0);
  const double offset = nt.dot(at);  // n·p of the tangent point p = c + r n
  SlabQuadric q;
  q.A = (2 * weight) * nt * nt.transpose();
  q.b = (2 * weight * offset) * nt;
  q.c = weight * offset * offset;
  return q;
}

PackedQuadric PackedQuadric::pack(const SlabQuadric& q) {
  PackedQuadric p;
  int k = 0;
  for (int r = 0; r < 4; ++r)
    for (int c = r; c < 4; ++c) {
      if (std::memcmp(&q.A(r, c), &q.A(c, r), sizeof(double)) != 0)
        throw std::logic_error("qmat: a vertex quadric is not exactly symmetric");
      p.upper[k++] = q.A(r, c);
    }
  for (int r = 0; r < 4; ++r) p.b[r] = q.b[r];
  p.c = q.c;
  return p;
}

PackedQuadric& PackedQuadric::operator+=(const PackedQuadric& o) {
  for (int k = 0; k < 10; ++k) upper[k] += o.upper[k];
  for (int r = 0; r < 4; ++r) b[r] += o.b[r];
  c += o.c;
  return *this;
}

namespace {

/// Step K of Eigen's unblocked partial-pivot LU of a fixed 4×4: pivot = first largest |entry| of
/// column K, row swap, column divided by the pivot, rank-one update of the trailing block. A
/// template, so that the compiler unrolls every loop.
template <int K>
void eliminate(double (&lu)[4][4], int (&pivot)[3]) {
  int p = K;
  double biggest = std::abs(lu[K][K]);
  for (int r = K + 1; r < 4; ++r)
    if (std::abs(lu[r][K]) > biggest) p = r, biggest = std::abs(lu[r][K]);
  pivot[K] = p;
  if (biggest != 0) {
    if (p != K)
      for (int c = 0; c < 4; ++c) std::swap(lu[K][c], lu[p][c]);
    for (int r = K + 1; r < 4; ++r) lu[r][K] /= lu[K][K];
  }
  for (int c = K + 1; c < 4; ++c)
    for (int r = K + 1; r < 4; ++r) lu[r][c] -= lu[K][c] * lu[r][K];
}

}  // namespace

Vec4 solve_partial_pivot(const Mat4& A, Vec4 x) {
  double lu[4][4];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) lu[r][c] = A(r, c);
  int pivot[3];
  eliminate<0>(lu, pivot);
  eliminate<1>(lu, pivot);
  eliminate<2>(lu, pivot);
  for (int k = 0; k < 3; ++k) std::swap(x[k], x[pivot[k]]);
  // Eigen's unrolled triangular solves: unit lower, then upper; the dot products of two or
  // three terms are summed as a₀ + a₁ and a₀ + (a₁ + a₂).
  x[1] -= lu[1][0] * x[0];
  x[2] -= lu[2][0] * x[0] + lu[2][1] * x[1];
  x[3] -= lu[3][0] * x[0] + (lu[3][1] * x[1] + lu[3][2] * x[2]);
  x[3] /= lu[3][3];
  x[2] -= lu[2][3] * x[3];
  x[2] /= lu[2][2];
  x[1] -= lu[1][2] * x[2] + lu[1][3] * x[3];
  x[1] /= lu[1][1];
  x[0] -= lu[0][1] * x[1] + (lu[0][2] * x[2] + lu[0][3] * x[3]);
  x[0] /= lu[0][0];
  return x;
}

std::optional<Vec4> SlabQuadric::solution() const {
  const Vec4 m = solve_partial_pivot(A, b);
  if (!m.allFinite()) return std::nullopt;
  return m;
}

std::optional<std::array<Vec3, 2>> slab_normals(const Vec4& m0, const Vec4& m1, const Vec4& m2,
                                                double min_distance) {
  const Vec3 e1 = centre_of(m1) - centre_of(m0), e2 = centre_of(m2) - centre_of(m0);
  if (e1.norm() < min_distance || e2.norm() < min_distance || (e2 - e1).norm() < min_distance) return std::nullopt;
  const Vec3 cross = e1.cross(e2);
  if (!(cross.norm() > 0)) return std::nullopt;
  const Vec3 normal = cross.normalized();
  // n∥ = α e1 + β e2 from the Gram system of n·eᵢ = r₀ − rᵢ.
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 0)) return std::nullopt;
  const double d1 = m0.w() - m1.w(), d2 = m0.w() - m2.w();
  const double alpha = (d1 * g22 - d2 * g12) / det, beta = (d2 * g11 - d1 * g12) / det;
  const Vec3 in_plane = alpha * e1 + beta * e2;
  const double sq = in_plane.squaredNorm();
  if (sq > 1) return std::nullopt;
  const double out = std::sqrt(1 - sq);
  return std::array<Vec3, 2>{Vec3(in_plane + out * normal), Vec3(in_plane - out * normal)};
}

double stability_ratio(const Vec4& mi, const Vec4& mj) {
  const double d = (centre_of(mi) - centre_of(mj)).norm();
  if (!(d > 0)) return 0;
  return std::max(0.0, d - std::abs(mi.w() - mj.w())) / d;
}

}  // namespace medax::qmat
