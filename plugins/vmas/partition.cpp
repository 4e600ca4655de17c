#include "partition.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <limits>

namespace medax::vmas {

void assign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                     std::vector<int>& cluster_of) {
  const std::size_t n = in.size(), count = spheres.size();
  cluster_of.assign(n, -1);
  if (count == 0) return;
  SphereTerms terms;
  terms.set(spheres);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<double> e(count);
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      if (!in.active(static_cast<Index>(v))) continue;
      const PackedQuadric& Q = in.quadrics[v];
      const Vec3& p = in.points[v];
      const double w = lambda * in.areas[v];
      // Structure of arrays over the spheres: this loop vectorises.
      const auto& m = terms.m;
      for (std::size_t j = 0; j < count; ++j) {
        const double mj[14] = {m[0][j], m[1][j], m[2][j],  m[3][j],  m[4][j],  m[5][j],  m[6][j],
                               m[7][j], m[8][j], m[9][j], m[10][j], m[11][j], m[12][j], m[13][j]};
        e[j] = vertex_energy(Q, p, w, mj);
      }
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
