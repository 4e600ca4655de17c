// MEDIAL passes B–C (Dey & Zhao 2004): poles and umbrellas.
#include "medial_passes.hpp"

#include <medax/services/blocks.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

namespace medax::dey_zhao {

using services::DelaunayTetrahedralization;

namespace {

/// Circumradius of the triangle (a, b, c): |u||v||u − v| / (2 |u × v|), u = b − a, v = c − a.
inline double circumradius(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a;
  const double area2 = u.cross(v).norm();
  return area2 > 0 ? u.norm() * v.norm() * (u - v).norm() / (2 * area2) : std::numeric_limits<double>::infinity();
}

/// max on non-negative doubles stored as their bit patterns (monotone for x ≥ 0, +inf included).
inline void atomic_max(std::atomic<std::uint64_t>& slot, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  std::uint64_t current = slot.load(std::memory_order_relaxed);
  while (bits > current && !slot.compare_exchange_weak(current, bits, std::memory_order_relaxed)) {
  }
}

/// B. Pole: the farthest Voronoi vertex of V_p (ties: the lowest cell). On the hull, V_p is
/// unbounded: v_p is the normalised sum of the unit outward normals of the hull facets at p,
/// the directions of V_p's infinite edges. Fills u.pole_vector and u.on_hull.
void compute_poles(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, Umbrellas& u) {
  const std::size_t n = dt.cells.size(), np = P.size();
  const auto& cc = dt.circumcentres;
  std::vector<double> best(np, -1.0);
  std::vector<Index> farthest(np, kNone);
  std::vector<Vec3> hull(np, Vec3::Zero());
  u.on_hull.assign(np, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const auto& corner = dt.cells[c];
    for (int k = 0; k < 4; ++k) {
      const Index x = corner[k];
      const double d2 = (cc[c] - P[x]).squaredNorm();
      if (d2 > best[x]) best[x] = d2, farthest[x] = static_cast<Index>(c);
    }
    for (int k = 0; k < 4; ++k)
      if (dt.neighbours[c][k] == kInf) {
        const Vec3 nt = unit(outward_normal(P, corner, k));
        for (int j = 0; j < 4; ++j)
          if (j != k) hull[corner[j]] += nt, u.on_hull[corner[j]] = 1;
      }
  }
  u.pole_vector.resize(np);
  for (std::size_t x = 0; x < np; ++x)
    u.pole_vector[x] = u.on_hull[x] ? unit(hull[x])
                       : farthest[x] != kNone ? unit(cc[farthest[x]] - P[x])
                                              : Vec3(Vec3::Zero());
}

/// Which Delaunay facets are in which umbrellas, and per point its umbrella's size and largest
/// circumradius.
struct UmbrellaFacets {
  std::vector<std::uint16_t> mask;  ///< per cell, bit 3k + m: facet k is in the umbrella of its m-th corner
  std::unique_ptr<std::atomic<std::uint32_t>[]> count;       ///< per point: umbrella triangles
  std::unique_ptr<std::atomic<std::uint64_t>[]> max_radius;  ///< per point: bits of the largest circumradius
};

/// C. Umbrella of p: the Delaunay triangles at p whose dual Voronoi edge crosses the plane
/// through p normal to v_p. sgn'(x) = (x >= 0 ? + : −) is an infinitesimally shifted plane.
/// Each facet is visited once, from its lower cell (or its only finite cell on the hull).
UmbrellaFacets find_umbrella_facets(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt,
                                    const std::vector<Vec3>& v, bool parallel) {
  const std::size_t n = dt.cells.size(), np = P.size();
  const auto& cc = dt.circumcentres;
  UmbrellaFacets out;
  out.count = std::make_unique<std::atomic<std::uint32_t>[]>(np);
  out.max_radius = std::make_unique<std::atomic<std::uint64_t>[]>(np);
  out.mask.assign(n, 0);
  services::for_blocks(n, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const auto& corner = dt.cells[c];
      std::uint16_t bits = 0;
      for (int k = 0; k < 4; ++k) {
        const std::int64_t nb = dt.neighbours[c][k];
        if (nb != kInf && nb < static_cast<std::int64_t>(c)) continue;
        const auto f = facet_corners(corner, k);
        Vec3 ray = Vec3::Zero();
        if (nb == kInf) ray = outward_normal(P, corner, k);
        int hits = 0;
        for (int m = 0; m < 3; ++m) {
          const Index x = f[m];
          const double s1 = (cc[c] - P[x]).dot(v[x]);
          const double s2 = nb == kInf ? ray.dot(v[x]) : (cc[nb] - P[x]).dot(v[x]);
          if ((s1 >= 0) != (s2 >= 0)) bits |= static_cast<std::uint16_t>(1u << (3 * k + m)), ++hits;
        }
        if (!hits) continue;
        const double r = circumradius(P[f[0]], P[f[1]], P[f[2]]);
        for (int m = 0; m < 3; ++m)
          if (bits & (1u << (3 * k + m))) {
            out.count[f[m]].fetch_add(1, std::memory_order_relaxed);
            atomic_max(out.max_radius[f[m]], r);
          }
      }
      out.mask[c] = bits;
    }
  });
  return out;
}

/// C, stored: the umbrellas as flat arrays (offsets per point, unit normals, triangles when
/// asked for) and the largest circumradius per point.
void fill_umbrellas(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, UmbrellaFacets& facets,
                    bool keep_triangles, bool parallel, Umbrellas& u) {
  const std::size_t n = dt.cells.size(), np = P.size();
  auto& count = facets.count;
  const auto& mask = facets.mask;
  u.offsets.assign(np + 1, 0);
  u.max_radius.resize(np);
  for (std::size_t x = 0; x < np; ++x) {
    u.offsets[x + 1] = u.offsets[x] + count[x].load(std::memory_order_relaxed);
    const std::uint64_t bits = facets.max_radius[x].load(std::memory_order_relaxed);
    std::memcpy(&u.max_radius[x], &bits, sizeof bits);
  }
  u.normals.resize(u.offsets[np]);
  if (keep_triangles) u.triangles.resize(u.offsets[np]);
  for (std::size_t x = 0; x < np; ++x) count[x].store(0, std::memory_order_relaxed);  // reused as cursors
  services::for_blocks(n, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      if (!mask[c]) continue;
      const auto& corner = dt.cells[c];
      for (int k = 0; k < 4; ++k) {
        if (!((mask[c] >> (3 * k)) & 7u)) continue;
        const auto f = facet_corners(corner, k);
        const Vec3 normal = unit((P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]));
        for (int m = 0; m < 3; ++m)
          if (mask[c] & (1u << (3 * k + m))) {
            const std::size_t slot = u.offsets[f[m]] + count[f[m]].fetch_add(1, std::memory_order_relaxed);
            u.normals[slot] = normal;
            if (keep_triangles) u.triangles[slot] = {f[0], f[1], f[2]};
          }
      }
    }
  });
}

}  // namespace

Umbrellas compute_umbrellas(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, bool keep_triangles,
                            bool parallel) {
  Umbrellas u;
  compute_poles(P, dt, u);
  UmbrellaFacets facets = find_umbrella_facets(P, dt, u.pole_vector, parallel);
  fill_umbrellas(P, dt, facets, keep_triangles, parallel, u);
  return u;
}

}  // namespace medax::dey_zhao
