#include "candidates.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/kdtree.hpp>

#include <fmt/format.h>

#include <stdexcept>

namespace medax::coverage_axis {

namespace {

/// `count` points uniform in the box [lo, hi].
std::vector<Vec3> uniform_in_box(const Vec3& lo, const Vec3& hi, std::size_t count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points(count);
  for (Vec3& p : points)
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + unit(rng) * (hi[k] - lo[k]);
  return points;
}

}  // namespace

std::vector<Vec3> random_interior_points(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const services::InsideTest inside(mesh);
  std::vector<Vec3> kept;
  kept.reserve(count);
  const std::size_t batch = std::max<std::size_t>(count, 1024);
  std::size_t drawn = 0;
  while (kept.size() < count) {
    // Points outside the box are never inside, so the box draws what the authors' larger box does.
    const std::vector<Vec3> points = uniform_in_box(lo, hi, batch, rng);
    const std::vector<char> in = inside.inside(points);
    for (std::size_t i = 0; i < points.size() && kept.size() < count; ++i)
      if (in[i]) kept.push_back(points[i]);
    drawn += batch;
    if (drawn >= 1000 * std::max<std::size_t>(count, 1) && kept.size() < count)
      throw std::runtime_error(fmt::format("only {} of {} random points fell inside the mesh; is it closed and "
                                           "outward oriented? (run `repair` first)",
                                           kept.size(), drawn));
  }
  return kept;
}

std::vector<double> candidate_radii(const std::vector<Vec3>& centres, const SurfaceMesh& mesh,
                                    const std::vector<Vec3>& samples, RadiusFrom from) {
  if (from == RadiusFrom::Mesh) return services::SurfaceDistance(mesh).distances(centres);
  const services::PointIndex index(samples);
  std::vector<double> radii(centres.size());
  for (std::size_t i = 0; i < centres.size(); ++i) radii[i] = index.nearest(centres[i]).second;
  return radii;
}

Balls complex_balls(const MedialComplex& medial) { return {medial.centres, medial.radii}; }

}  // namespace medax::coverage_axis
