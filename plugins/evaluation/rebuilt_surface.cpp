#include "rebuilt_surface.hpp"

#include <medax/services/sampling.hpp>

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace medax::evaluation {

namespace {

/// Largest and mean value (0 for none).
std::pair<double, double> max_and_mean(const std::vector<double>& values) {
  if (values.empty()) return {0.0, 0.0};
  double sum = 0, mx = 0;
  for (double v : values) {
    sum += v;
    mx = std::max(mx, v);
  }
  return {mx, sum / static_cast<double>(values.size())};
}

}  // namespace

Metrics RebuiltSurfaceResult::metrics() const {
  Metrics m;
  m["bbox_diagonal"] = diagonal;
  m["surface_samples"] = static_cast<double>(surface_samples);
  m["rebuilt_samples"] = static_cast<double>(rebuilt_samples);
  m["rebuilt_area"] = rebuilt_area;
  add_distance(m, "surface_to_rebuilt_max", surface_to_rebuilt_max, diagonal);
  add_distance(m, "surface_to_rebuilt_mean", surface_to_rebuilt_mean, diagonal);
  add_distance(m, "rebuilt_to_surface_max", rebuilt_to_surface_max, diagonal);
  add_distance(m, "rebuilt_to_surface_mean", rebuilt_to_surface_mean, diagonal);
  add_distance(m, "hausdorff", hausdorff(), diagonal);
  add_distance(m, "eps1", eps1(), diagonal);
  add_distance(m, "eps2", eps2(), diagonal);
  add_distance(m, "eps", eps(), diagonal);
  return m;
}

RebuiltSurfaceResult measure_rebuilt_surface(const Shape& shape, const SurfaceMesh& rebuilt,
                                             const ReconstructionOptions& options, std::mt19937_64& rng,
                                             const services::CancelCheck& cancel) {
  if (shape.mesh.empty() && shape.samples.empty())
    throw std::invalid_argument("the shape has neither a mesh nor samples to compare with");
  if (rebuilt.faces.empty())
    throw std::invalid_argument("the rebuilt surface has no faces; the stage that published it made nothing");
  RebuiltSurfaceResult result;
  result.diagonal = shape_diagonal(shape);
  const std::vector<Vec3> surface = shape_samples(shape, options, rng);
  if (surface.empty()) throw std::invalid_argument("no surface samples (vertices: false and surface_samples: 0)");
  Shape rebuilt_shape;  // sampled and searched as a shape is
  rebuilt_shape.mesh = rebuilt;
  const std::vector<Vec3> rebuilt_points = shape_samples(rebuilt_shape, options, rng);
  result.surface_samples = surface.size();
  result.rebuilt_samples = rebuilt_points.size();
  result.rebuilt_area = services::surface_area(rebuilt);
  std::tie(result.surface_to_rebuilt_max, result.surface_to_rebuilt_mean) =
      max_and_mean(distances_to_shape(rebuilt_shape, surface, cancel));
  std::tie(result.rebuilt_to_surface_max, result.rebuilt_to_surface_mean) =
      max_and_mean(distances_to_shape(shape, rebuilt_points, cancel));
  return result;
}

}  // namespace medax::evaluation
