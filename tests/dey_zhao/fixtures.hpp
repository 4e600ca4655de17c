#pragma once
// Shared fixtures of the dey_zhao tests: Poisson samples of analytic shapes, moved onto the
// smooth surface, with their exact normals; quantiles; a one-call MEDIAL.
#include "medial.hpp"

#include <medax/services/poisson.hpp>
#include <medax/testing/shapes.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace medax::dz_test {

/// Surface samples with exact outward normals, and a fine mesh of the same surface (for the
/// mesh inner selection and the voronoi baseline).
struct Sampled {
  SurfaceMesh mesh;
  std::vector<Vec3> points, normals;
};

/// Ellipsoid a > b > c: Poisson-disk samples of a fine icosphere mesh, scaled onto the exact
/// ellipsoid along their position vectors.
inline Sampled ellipsoid(double a, double b, double c, std::size_t n, std::uint64_t seed = 7) {
  Sampled s;
  s.mesh = testing::make_ellipsoid(a, b, c, 6);
  std::mt19937_64 rng(seed);
  const OrientedSamples o = services::sample_poisson_count(s.mesh, n, rng);
  for (const Vec3& p : o.points) {
    const Vec3 q = p / std::sqrt(p.x() * p.x() / (a * a) + p.y() * p.y() / (b * b) + p.z() * p.z() / (c * c));
    s.points.push_back(q);
    s.normals.push_back(Vec3(q.x() / (a * a), q.y() / (b * b), q.z() / (c * c)).normalized());
  }
  return s;
}

/// Torus (R, r) around z: Poisson-disk samples of a fine mesh, moved to the closest point of the
/// exact torus.
inline Sampled torus(double R, double r, std::size_t n, std::uint64_t seed = 7) {
  Sampled s;
  s.mesh = testing::make_torus(R, r, 256, 64);
  std::mt19937_64 rng(seed);
  const OrientedSamples o = services::sample_poisson_count(s.mesh, n, rng);
  for (const Vec3& p : o.points) {
    const Vec3 ring = R * Vec3(p.x(), p.y(), 0).normalized();
    const Vec3 normal = (p - ring).normalized();
    s.points.push_back(ring + r * normal);
    s.normals.push_back(normal);
  }
  return s;
}

inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

/// MEDIAL on the samples, with the mesh and the normals available to the inner selection.
inline MedialComplex run(const Sampled& s, dey_zhao::MedialOptions options = {},
                         dey_zhao::MedialReport* report = nullptr) {
  dey_zhao::MedialInput in;
  in.points = &s.points;
  in.normals = &s.normals;
  in.mesh = &s.mesh;
  options.generator_kind = "sample";
  return dey_zhao::medial_axis(in, options, report);
}

inline dey_zhao::MedialOptions with_inner(dey_zhao::InnerSelection inner) {
  dey_zhao::MedialOptions o;
  o.inner = inner;
  return o;
}

}  // namespace medax::dz_test
