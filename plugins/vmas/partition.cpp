#include "partition.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

}  // namespace

void assign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                     std::vector<int>& cluster_of) {
  const std::size_t n = in.size(), count = spheres.size();
  cluster_of.assign(n, -1);
  if (count == 0) return;
  SphereTerms terms;
  terms.set(spheres);
  const double* columns[14];
  for (int i = 0; i < 14; ++i) columns[i] = terms.m[i].data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<double> e(count);
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      if (!in.active(static_cast<Index>(v))) continue;
      const Vec3& p = in.points[v];
      energies(in.quadrics[v], p.x(), p.y(), p.z(), lambda * in.areas[v], columns, count, e.data());
      std::size_t best = 0;
      double best_e = e[0];
      for (std::size_t j = 1; j < count; ++j)
        if (e[j] < best_e) best_e = e[j], best = j;
      cluster_of[v] = static_cast<int>(best);
    }
  });
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
