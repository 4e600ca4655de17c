#pragma once
// Point clouds of analytic surfaces (sphere, ellipsoid, torus) with their exact outward normals,
// uniform in area (rejection sampling, seeded), and the corruptions a scan brings: noise, flipped
// or missing normals, outliers, a patch cut out.
#include <medax/io.hpp>
#include <medax/surface.hpp>

#include <cmath>
#include <random>

namespace medax::test {

/// Equal areas summing to the estimated surface area, as read_point_set gives them.
inline void share_areas(OrientedSamples& cloud) {
  cloud.areas.assign(cloud.size(), estimate_surface_area(cloud.points) / static_cast<double>(cloud.size()));
}

/// Uniform in area on the ellipsoid x²/a² + y²/b² + z²/c² = 1 (a sphere when a = b = c): a unit
/// direction u maps to (a u_x, b u_y, c u_z), kept with probability ∝ its area element.
inline OrientedSamples ellipsoid_cloud(double a, double b, double c, std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0, 1);
  const double largest = std::max({b * c, a * c, a * b});
  OrientedSamples cloud;
  while (cloud.size() < n) {
    const Vec3 u = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vec3 gradient(u.x() * b * c, u.y() * a * c, u.z() * a * b);  // ∝ area element and normal
    if (uniform(rng) * largest > gradient.norm()) continue;
    cloud.points.emplace_back(a * u.x(), b * u.y(), c * u.z());
    cloud.normals.push_back(gradient.normalized());
  }
  share_areas(cloud);
  return cloud;
}

/// Uniform in area on the torus around z with core radius R and tube radius r.
inline OrientedSamples torus_cloud(double R, double r, std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  std::uniform_real_distribution<double> uniform(0, 1);
  OrientedSamples cloud;
  while (cloud.size() < n) {
    const double theta = angle(rng), phi = angle(rng);
    if (uniform(rng) * (R + r) > R + r * std::cos(phi)) continue;
    const Vec3 radial(std::cos(theta), std::sin(theta), 0);
    const Vec3 normal = std::cos(phi) * radial + std::sin(phi) * Vec3::UnitZ();
    cloud.points.push_back(R * radial + r * normal);
    cloud.normals.push_back(normal);
  }
  share_areas(cloud);
  return cloud;
}

/// Gaussian noise of standard deviation `sigma` on every coordinate.
inline void add_noise(OrientedSamples& cloud, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0, sigma);
  for (Vec3& p : cloud.points) p += Vec3(gauss(rng), gauss(rng), gauss(rng));
}

/// Reverses each normal with probability 1/2.
inline void flip_at_random(OrientedSamples& cloud, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution flip(0.5);
  for (Vec3& n : cloud.normals)
    if (flip(rng)) n = -n;
}

/// Removes the points within `radius` of `centre` (a hole in the scan).
inline void cut_patch(OrientedSamples& cloud, const Vec3& centre, double radius) {
  OrientedSamples kept;
  const bool normals = cloud.normals.size() == cloud.size();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if ((cloud.points[i] - centre).norm() < radius) continue;
    kept.points.push_back(cloud.points[i]);
    if (normals) kept.normals.push_back(cloud.normals[i]);
  }
  share_areas(kept);
  cloud = kept;
}

}  // namespace medax::test
