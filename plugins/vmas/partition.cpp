#include "partition.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace medax::vmas {

namespace {

/// E_v against every sphere, into e[0 .. count). Structure of arrays over the spheres, so the
/// loop vectorises. Same operations, in the same order, as vertex_energy() (energy.hpp), so both
/// give identical values.
__attribute__((noinline)) void energies(const PackedQuadric& Q, double px, double py, double pz, double w,
                                        const double* const* terms, std::size_t count, double* __restrict e) {
  const double k0 = Q.k[0], k1 = Q.k[1], k2 = Q.k[2], k3 = Q.k[3], k4 = Q.k[4], k5 = Q.k[5], k6 = Q.k[6],
               k7 = Q.k[7], k8 = Q.k[8], k9 = Q.k[9], k10 = Q.k[10], k11 = Q.k[11], k12 = Q.k[12], k13 = Q.k[13],
               c = Q.c;
  const double *__restrict m0 = terms[0], *__restrict m1 = terms[1], *__restrict m2 = terms[2],
               *__restrict m3 = terms[3], *__restrict m4 = terms[4], *__restrict m5 = terms[5],
               *__restrict m6 = terms[6], *__restrict m7 = terms[7], *__restrict m8 = terms[8],
               *__restrict m9 = terms[9], *__restrict m10 = terms[10], *__restrict m11 = terms[11],
               *__restrict m12 = terms[12], *__restrict m13 = terms[13];
  for (std::size_t j = 0; j < count; ++j) {
    const double q = c + k0 * m0[j] + k1 * m1[j] + k2 * m2[j] + k3 * m3[j] + k4 * m4[j] + k5 * m5[j] + k6 * m6[j] +
                     k7 * m7[j] + k8 * m8[j] + k9 * m9[j] + k10 * m10[j] + k11 * m11[j] + k12 * m12[j] +
                     k13 * m13[j];
    const double dx = px - m10[j], dy = py - m11[j], dz = pz - m12[j];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz) - m13[j];
    e[j] = q + w * d * d;
  }
}

/// The same value for one sphere j (same operations in the same order: identical results).
inline double energy_at(const PackedQuadric& Q, double px, double py, double pz, double w, const double* const* m,
                        std::size_t j) {
  const auto& k = Q.k;
  const double q = Q.c + k[0] * m[0][j] + k[1] * m[1][j] + k[2] * m[2][j] + k[3] * m[3][j] + k[4] * m[4][j] +
                   k[5] * m[5][j] + k[6] * m[6][j] + k[7] * m[7][j] + k[8] * m[8][j] + k[9] * m[9][j] +
                   k[10] * m[10][j] + k[11] * m[11][j] + k[12] * m[12][j] + k[13] * m[13][j];
  const double dx = px - m[10][j], dy = py - m[11][j], dz = pz - m[12][j];
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz) - m[13][j];
  return q + w * d * d;
}

/// keep[j] ≥ 0 unless sphere j surely cannot beat energy `bound`: since Q_v ≥ 0,
/// E_v(m_j) ≥ w·(|v − q_j| − r_j)², so j is out when ||v − q_j| − r_j| > δ = √(bound / w), i.e.
/// when |v − q_j|² > (r_j + δ)² or |v − q_j|² < max(r_j − δ, 0)². (Branch-free: vectorises.)
__attribute__((noinline)) void candidates(double px, double py, double pz, double delta, const double* __restrict qx,
                                          const double* __restrict qy, const double* __restrict qz,
                                          const double* __restrict r, std::size_t count, double* __restrict keep) {
  for (std::size_t j = 0; j < count; ++j) {
    const double dx = px - qx[j], dy = py - qy[j], dz = pz - qz[j];
    const double l2 = dx * dx + dy * dy + dz * dz;
    const double hi = r[j] + delta, lo = std::max(r[j] - delta, 0.0);
    keep[j] = std::min(hi * hi - l2, l2 - lo * lo);
  }
}

}  // namespace

void assign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                     std::vector<int>& cluster_of, const std::vector<int>* hint) {
  const std::size_t n = in.size(), count = spheres.size();
  std::vector<int> result(n, -1);
  if (count == 0) {
    cluster_of = std::move(result);
    return;
  }
  SphereTerms terms;
  terms.set(spheres);
  const double* columns[14];
  for (int i = 0; i < 14; ++i) columns[i] = terms.m[i].data();
  const double margin = 1e-12 * in.scale * in.scale;  // above the round-off of Q_v (per unit area)
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<double> e(count);
    std::vector<double> keep(count);
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      if (!in.active(static_cast<Index>(v))) continue;
      const Vec3& p = in.points[v];
      const PackedQuadric& Q = in.quadrics[v];
      const double w = lambda * in.areas[v];
      std::size_t best = 0;
      if (w > 0 && count > 8) {
        // Exact pruning: bound the minimum by the energy of a good guess (the previous cluster),
        // with a margin above round-off, then evaluate only the spheres that could beat it. The
        // result is the brute-force argmin, lowest index on ties.
        std::size_t guess = 0;
        if (hint && v < hint->size() && (*hint)[v] >= 0 && static_cast<std::size_t>((*hint)[v]) < count)
          guess = static_cast<std::size_t>((*hint)[v]);
        const double bound = energy_at(Q, p.x(), p.y(), p.z(), w, columns, guess) * (1 + 1e-9) + in.areas[v] * margin;
        const double delta = std::sqrt(std::max(bound, 0.0) / w);
        candidates(p.x(), p.y(), p.z(), delta, columns[10], columns[11], columns[12], columns[13], count, keep.data());
        double best_e = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < count; ++j) {
          if (!(keep[j] >= 0)) continue;
          const double ej = energy_at(Q, p.x(), p.y(), p.z(), w, columns, j);
          if (ej < best_e) best_e = ej, best = j;
        }
        if (!std::isfinite(best_e)) best = guess;
      } else {
        energies(Q, p.x(), p.y(), p.z(), w, columns, count, e.data());
        double best_e = e[0];
        for (std::size_t j = 1; j < count; ++j)
          if (e[j] < best_e) best_e = e[j], best = j;
      }
      result[v] = static_cast<int>(best);
    }
  });
  cluster_of = std::move(result);
}

Clusters group_clusters(const std::vector<int>& cluster_of, std::size_t sphere_count) {
  Clusters c;
  c.offsets.assign(sphere_count + 1, 0);
  for (int i : cluster_of)
    if (i >= 0) ++c.offsets[static_cast<std::size_t>(i) + 1];
  for (std::size_t i = 0; i < sphere_count; ++i) c.offsets[i + 1] += c.offsets[i];
  c.members.resize(c.offsets.back());
  std::vector<Index> fill(c.offsets.begin(), c.offsets.end() - 1);
  for (Index v = 0; v < cluster_of.size(); ++v)
    if (cluster_of[v] >= 0) c.members[fill[static_cast<std::size_t>(cluster_of[v])]++] = v;
  return c;
}

}  // namespace medax::vmas
