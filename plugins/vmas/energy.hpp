#pragma once
// The VMAS energy (notes §2.3–2.5):
//   E_v(m) = Q_v(m) + λ · A(v) · (|v − q| − r)²               (eq. 8, per vertex)
//   E(C)   = (1 / A(C)) Σ_{v∈C} E_v(m)                         (eq. 12, per cluster)
// One inline kernel evaluates E_v for the partition (vectorised over spheres) and for the
// cluster errors, so both see bit-identical values.
#include "input.hpp"

#include <cmath>
#include <vector>

namespace medax::vmas {

/// Spheres laid out for the partition kernel: the 14 monomials of each sphere, one array each
/// (m[10..13] are the sphere itself: q_x, q_y, q_z, r).
struct SphereTerms {
  std::array<std::vector<double>, 14> m;
  std::size_t size() const { return m[0].size(); }
  void set(const std::vector<Sphere>& spheres);
};

/// E_v for one sphere given its monomials; `w` = λ · A(v).
inline double vertex_energy(const PackedQuadric& Q, const Vec3& p, double w, const double* m) {
  const auto& k = Q.k;
  double e = Q.c + k[0] * m[0] + k[1] * m[1] + k[2] * m[2] + k[3] * m[3] + k[4] * m[4] + k[5] * m[5] +
             k[6] * m[6] + k[7] * m[7] + k[8] * m[8] + k[9] * m[9] + k[10] * m[10] + k[11] * m[11] +
             k[12] * m[12] + k[13] * m[13];
  const double dx = p.x() - m[10], dy = p.y() - m[11], dz = p.z() - m[12];
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz) - m[13];
  return e + w * d * d;
}

/// E_v(m) for a vertex of the input (eq. 8), with the paper's quadric.
inline double vertex_energy(const VmasInput& in, Index v, const Sphere& s, double lambda) {
  const auto m = monomials(s);
  return vertex_energy(in.quadrics[v], in.points[v], lambda * in.areas[v], m.data());
}

struct ClusterStats {
  double energy = 0;  ///< Σ_{v∈C} E_v (not normalised)
  double area = 0;    ///< A(C)
  double error = 0;   ///< E(C) = energy / area (eq. 12)
  Index split_vertex = 0;  ///< argmax_{v∈C} E_v (lowest index on ties)
  double split_energy = -1;
};

/// Statistics of one cluster (members in ascending order) against its sphere, with the Q_v of
/// `quadrics` (the input's, or vertex_normal_quadrics()).
ClusterStats cluster_stats(const VmasInput& in, const std::vector<PackedQuadric>& quadrics, const Index* members,
                           std::size_t count, const Sphere& s, double lambda);

/// Which SQEM term the partition and the cluster errors use (eq. 8).
enum class PartitionSqem {
  Diffused,      ///< Q_v of eq. 7: the planes of v's faces, each weighted A(t)/3 (the paper, CGoGN)
  VertexNormal,  ///< A(v)·((v − q)·n_v − r)²: one plane, v's normal (the CGAL port)
};

/// The VertexNormal quadrics, per vertex.
std::vector<PackedQuadric> vertex_normal_quadrics(const VmasInput& in);

}  // namespace medax::vmas
