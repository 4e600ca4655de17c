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

/// The spheres packed for the kernels above, with the pruning margin.
class Searcher {
 public:
  Searcher(const VmasInput& in, const std::vector<PackedQuadric>& quadrics, const std::vector<Sphere>& spheres,
           double lambda)
      : in_(in), quadrics_(quadrics), lambda_(lambda) {
    terms_.set(spheres);
    for (int i = 0; i < 14; ++i) columns_[i] = terms_.m[i].data();
  }
  std::size_t count() const { return terms_.size(); }

  /// E_v of sphere j.
  double energy(Index v, std::size_t j) const {
    const Vec3& p = in_.points[v];
    return energy_at(quadrics_[v], p.x(), p.y(), p.z(), weight(v), columns_, j);
  }

  /// The argmin over every sphere, lowest index on ties. `guess` only prunes: spheres that
  /// provably cannot beat it are not evaluated.
  std::size_t best_of_all(Index v, std::size_t guess, std::vector<double>& scratch) const {
    const std::size_t count = this->count();
    const double w = weight(v);
    const Vec3& p = in_.points[v];
    scratch.resize(count);
    std::size_t best = 0;
    if (w > 0 && count > 8) {
      // Exact pruning: bound the minimum by the guess's energy, then evaluate only the spheres
      // that could beat it.
      const double e_guess = energy(v, guess);
      candidates(p.x(), p.y(), p.z(), reach(v, e_guess), columns_[10], columns_[11], columns_[12], columns_[13],
                 count, scratch.data());
      double best_e = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < count; ++j) {
        if (!(scratch[j] >= 0)) continue;
        const double ej = energy(v, j);
        if (ej < best_e) best_e = ej, best = j;
      }
      return std::isfinite(best_e) ? best : guess;
    }
    energies(quadrics_[v], p.x(), p.y(), p.z(), w, columns_, count, scratch.data());
    double best_e = scratch[0];
    for (std::size_t j = 1; j < count; ++j)
      if (scratch[j] < best_e) best_e = scratch[j], best = j;
    return best;
  }

  /// The argmin over {current} ∪ `subset` (ascending indices), lowest index on ties; the
  /// spheres of `subset` are packed in `packed`, in the same order.
  std::size_t best_of_subset(Index v, std::size_t current, const std::vector<std::size_t>& subset,
                             const Searcher& packed, std::vector<double>& scratch) const {
    const double e_current = energy(v, current);
    if (subset.empty()) return current;
    const double w = weight(v);
    const Vec3& p = in_.points[v];
    scratch.resize(subset.size());
    if (w > 0)
      candidates(p.x(), p.y(), p.z(), reach(v, e_current), packed.columns_[10], packed.columns_[11],
                 packed.columns_[12], packed.columns_[13], subset.size(), scratch.data());
    else
      std::fill(scratch.begin(), scratch.end(), 0.0);
    std::size_t best = current;
    double best_e = e_current;
    for (std::size_t k = 0; k < subset.size(); ++k) {
      if (!(scratch[k] >= 0)) continue;
      const double ek = packed.energy(v, k);  // the same operations on the same numbers as energy(v, subset[k])
      if (ek < best_e || (ek == best_e && subset[k] < best)) best_e = ek, best = subset[k];
    }
    return best;
  }

 private:
  double weight(Index v) const { return lambda_ * in_.areas[v]; }
  /// How far |v − q| − r may be from 0 for a sphere to beat energy e: √(e / w), with a margin
  /// above the round-off of Q_v (per unit area).
  double reach(Index v, double e) const {
    const double margin = 1e-12 * in_.scale * in_.scale;
    const double bound = e * (1 + 1e-9) + in_.areas[v] * margin;
    return std::sqrt(std::max(bound, 0.0) / weight(v));
  }

  const VmasInput& in_;
  const std::vector<PackedQuadric>& quadrics_;
  double lambda_;
  SphereTerms terms_;
  const double* columns_[14];
};

}  // namespace

void assign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                     std::vector<int>& cluster_of, const std::vector<int>* hint,
                     const std::vector<PackedQuadric>* quadrics) {
  const std::size_t n = in.size(), count = spheres.size();
  std::vector<int> result(n, -1);
  if (count == 0) {
    cluster_of = std::move(result);
    return;
  }
  const Searcher all(in, quadrics ? *quadrics : in.quadrics, spheres, lambda);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<double> scratch;
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      if (!in.active(static_cast<Index>(v))) continue;
      std::size_t guess = 0;
      if (hint && v < hint->size() && (*hint)[v] >= 0 && static_cast<std::size_t>((*hint)[v]) < count)
        guess = static_cast<std::size_t>((*hint)[v]);
      result[v] = static_cast<int>(all.best_of_all(static_cast<Index>(v), guess, scratch));
    }
  });
  cluster_of = std::move(result);
}

void reassign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                       const std::vector<char>& moved, std::vector<int>& cluster_of,
                       const std::vector<PackedQuadric>* quadrics) {
  const std::size_t n = in.size(), count = spheres.size();
  if (count == 0 || cluster_of.size() != n || moved.size() != count) {
    assign_vertices(in, spheres, lambda, cluster_of, cluster_of.size() == n ? &cluster_of : nullptr, quadrics);
    return;
  }
  std::vector<std::size_t> subset;
  std::vector<Sphere> subset_spheres;
  for (std::size_t j = 0; j < count; ++j)
    if (moved[j]) subset.push_back(j), subset_spheres.push_back(spheres[j]);
  const auto& q = quadrics ? *quadrics : in.quadrics;
  const Searcher all(in, q, spheres, lambda), packed(in, q, subset_spheres, lambda);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<double> scratch;
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      if (!in.active(static_cast<Index>(v))) continue;
      const int c = cluster_of[v];
      const bool assigned = c >= 0 && static_cast<std::size_t>(c) < count;
      const std::size_t current = assigned ? static_cast<std::size_t>(c) : 0;
      // A vertex whose sphere did not move was at the argmin: only a moved sphere can beat it.
      const std::size_t best = assigned && !moved[current]
                                   ? all.best_of_subset(static_cast<Index>(v), current, subset, packed, scratch)
                                   : all.best_of_all(static_cast<Index>(v), current, scratch);
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
