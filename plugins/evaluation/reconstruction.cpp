#include "reconstruction.hpp"

#include <medax/ply.hpp>
#include <medax/services/closest_point.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/services/sampling.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <exception>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace medax::evaluation {

namespace {

const std::vector<Vec3>& surface_points(const Shape& shape) {
  return shape.mesh.empty() ? shape.samples.points : shape.mesh.vertices;
}

std::pair<Vec3, Vec3> bbox(const std::vector<Vec3>& points) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

/// Smallest positive side of a box, or its diagonal when it is flat in every direction.
double smallest_side(const Vec3& lo, const Vec3& hi) {
  double side = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
    if (hi[k] - lo[k] > 0) side = std::min(side, hi[k] - lo[k]);
  return std::isfinite(side) ? side : (hi - lo).norm();
}

}  // namespace

double envelope_step(const Shape& shape, const services::Envelope& envelope, const ReconstructionOptions& options) {
  if (options.step > 0) return options.step;
  const auto [slo, shi] = bbox(surface_points(shape));
  const auto [elo, ehi] = envelope.bounds();
  // The envelope's own size too, so that an envelope much smaller than the shape is still
  // sampled at `resolution` points across.
  return std::min(smallest_side(slo, shi), smallest_side(elo, ehi)) / std::max(1, options.resolution);
}

void add_distance(Metrics& m, const std::string& name, double value, double diagonal) {
  m[name] = value;
  m[name + "_pct"] = diagonal > 0 ? 100.0 * value / diagonal : 0.0;
}

double shape_diagonal(const Shape& shape) {
  const auto [lo, hi] = bbox(surface_points(shape));
  return (hi - lo).norm();
}

Metrics ReconstructionResult::metrics() const {
  Metrics m;
  const auto both = [&](const std::string& name, double value) { add_distance(m, name, value, diagonal); };
  m["bbox_diagonal"] = diagonal;
  m["envelope_step"] = step;
  m["envelope_primitives"] = static_cast<double>(primitives);
  m["envelope_samples"] = static_cast<double>(envelope.size());
  m["envelope_area"] = envelope_area;
  m["surface_samples"] = static_cast<double>(surface_samples);
  m["surface_inside_fraction"] = surface_inside_fraction;
  both("surface_to_envelope_max", surface_to_envelope_max);
  both("surface_to_envelope_mean", surface_to_envelope_mean);
  both("envelope_to_surface_max", envelope_to_surface_max);
  both("envelope_to_surface_mean", envelope_to_surface_mean);
  both("hausdorff", hausdorff());
  both("eps1", eps1());
  both("eps2", eps2());
  both("eps", eps());
  return m;
}

/// As the VMAS code does, the vertices are those that faces use.
std::vector<Vec3> shape_samples(const Shape& shape, const ReconstructionOptions& options, std::mt19937_64& rng) {
  if (shape.mesh.empty()) return shape.samples.points;
  std::vector<Vec3> surface;
  if (options.use_vertices) {
    std::vector<char> used(shape.mesh.vertices.size(), 0);
    for (const Tri& f : shape.mesh.faces)
      for (Index v : f) used.at(v) = 1;
    for (std::size_t v = 0; v < used.size(); ++v)
      if (used[v]) surface.push_back(shape.mesh.vertices[v]);
  }
  if (options.uniform_samples > 0) {
    const OrientedSamples s = services::sample_uniform(shape.mesh, options.uniform_samples, rng);
    surface.insert(surface.end(), s.points.begin(), s.points.end());
  }
  return surface;
}

ShapeDistance::ShapeDistance(const Shape& shape) {
  if (!shape.mesh.empty()) mesh_ = std::make_unique<services::SurfaceDistance>(shape.mesh);
  else samples_ = std::make_unique<services::PointIndex>(shape.samples.points);
}

ShapeDistance::~ShapeDistance() = default;

std::vector<double> ShapeDistance::distances(const std::vector<Vec3>& points,
                                             const services::CancelCheck& cancel) const {
  constexpr std::size_t kBlock = 8192;  // about 10 ms of queries
  std::vector<double> out(points.size());
  for (std::size_t begin = 0; begin < points.size(); begin += kBlock) {
    if (cancel) cancel();
    const std::vector<Vec3> block(points.begin() + begin, points.begin() + std::min(points.size(), begin + kBlock));
    std::vector<double> d;
    if (mesh_) {
      d = mesh_->distances(block);
    } else {
      for (const Vec3& p : block) d.push_back(samples_->nearest(p).second);
    }
    std::copy(d.begin(), d.end(), out.begin() + begin);
  }
  return out;
}

std::vector<double> distances_to_shape(const Shape& shape, const std::vector<Vec3>& points,
                                       const services::CancelCheck& cancel) {
  return ShapeDistance(shape).distances(points, cancel);
}

namespace {

/// `step` enlarged, when the options' guard asks for it, so that ∂E gets at most about
/// max_envelope_samples points: about 1.5 points per step² of boundary (‖n‖₁ averages 1.5),
/// and ∂E ≈ the surface.
double budgeted_step(const Shape& shape, const ReconstructionOptions& options, double step) {
  if (options.max_envelope_samples == 0 || options.step > 0) return step;
  double area = 0;
  if (!shape.mesh.empty()) {
    area = services::surface_area(shape.mesh);
  } else {
    for (double a : shape.samples.areas) area += a;
  }
  const double budget = static_cast<double>(options.max_envelope_samples);
  return 1.5 * area / (step * step) > budget ? std::sqrt(1.5 * area / budget) : step;
}

/// Surface -> envelope: distances from the surface samples to ∂E.
void measure_surface_to_envelope(const services::Envelope& envelope, const std::vector<Vec3>& surface,
                                 ReconstructionResult& result, const services::CancelCheck& cancel) {
  std::vector<double> phi;
  // When the budget enlarged the step, the inside distances that the samples only bound are
  // tightened on the grid of the step asked for (docs/plugins/evaluation.md).
  const double refine_step = result.step > result.requested_step ? result.requested_step : 0.0;
  const std::vector<double> s2e = envelope.boundary_distances(surface, result.envelope, &phi, cancel, refine_step);
  std::size_t inside = 0;
  double sum = 0, mx = 0;
  for (std::size_t i = 0; i < surface.size(); ++i) {
    if (phi[i] < 0) ++inside;
    sum += s2e[i];
    mx = std::max(mx, s2e[i]);
  }
  result.surface_inside_fraction = static_cast<double>(inside) / static_cast<double>(surface.size());
  result.surface_to_envelope_max = mx;
  result.surface_to_envelope_mean = sum / static_cast<double>(surface.size());
}

/// Envelope -> surface: distances from the points of ∂E to the mesh (or the nearest sample),
/// the mean weighted by area.
void measure_envelope_to_surface(const ShapeDistance& to_shape, ReconstructionResult& result,
                                 const services::CancelCheck& cancel) {
  if (result.envelope.size() == 0) return;
  result.envelope_distances = to_shape.distances(result.envelope.points, cancel);
  double weighted = 0, area = 0, mx = 0;
  for (std::size_t i = 0; i < result.envelope.size(); ++i) {
    weighted += result.envelope.areas[i] * result.envelope_distances[i];
    area += result.envelope.areas[i];
    mx = std::max(mx, result.envelope_distances[i]);
  }
  result.envelope_to_surface_max = mx;
  result.envelope_to_surface_mean = area > 0 ? weighted / area : 0.0;
}

/// Runs a job on the task scheduler beside the caller's work; wait() rethrows what it threw. The
/// destructor waits too (so that an exception of the caller's work leaves nothing running).
class BackgroundTask {
 public:
  explicit BackgroundTask(std::function<void()> job) {
    group_.run([this, job = std::move(job)] {
      try {
        job();
      } catch (...) {
        error_ = std::current_exception();
      }
    });
  }
  ~BackgroundTask() { group_.wait(); }
  void wait() {
    group_.wait();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  tbb::task_group group_;
  std::exception_ptr error_;
};

}  // namespace

ReconstructionResult measure_reconstruction(const Shape& shape, const MedialComplex& medial,
                                            const ReconstructionOptions& options, std::mt19937_64& rng,
                                            const Progress& progress, const services::CancelCheck& cancel) {
  const auto report = [&](double f, std::string_view what) {
    if (progress) progress(f, what);
  };
  if (shape.mesh.empty() && shape.samples.empty())
    throw std::invalid_argument("the shape has neither a mesh nor samples to compare with");
  if (medial.num_vertices() == 0) throw std::invalid_argument("the medial complex is empty");

  ReconstructionResult result;
  result.diagonal = shape_diagonal(shape);
  const std::vector<Vec3> surface = shape_samples(shape, options, rng);
  if (surface.empty())
    throw std::invalid_argument("no surface samples (vertices: false and surface_samples: 0)");
  result.surface_samples = surface.size();

  // The shape's distance tree does not depend on the envelope: it is built beside the sampling.
  std::unique_ptr<ShapeDistance> to_shape;
  BackgroundTask build_to_shape([&] { to_shape = std::make_unique<ShapeDistance>(shape); });

  report(0.0, "envelope");
  const services::Envelope envelope(medial);
  result.primitives = envelope.primitives().size();
  result.requested_step = envelope_step(shape, envelope, options);
  result.step = budgeted_step(shape, options, result.requested_step);
  result.envelope =
      envelope.sample_boundary(result.step, [&](double f) { report(0.05 + 0.6 * f, "envelope boundary"); }, cancel);
  result.envelope_area = result.envelope.total_area();

  // The two directions at once: each has sequential parts (its search structure) that the
  // other fills.
  report(0.65, "distances");
  build_to_shape.wait();
  tbb::parallel_invoke([&] { measure_surface_to_envelope(envelope, surface, result, cancel); },
                       [&] { measure_envelope_to_surface(*to_shape, result, cancel); });
  report(1.0, "done");
  return result;
}

void write_envelope_ply(std::ostream& out, const ReconstructionResult& result, const Similarity& frame) {
  const services::EnvelopeSamples& e = result.envelope;
  std::vector<Vec3> points(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) points[i] = frame.apply(e.points[i]);
  PlyElement vertex("vertex", e.size());
  vertex.positions(points)
      .real("nx", [&e](std::size_t i) { return e.normals[i].x(); })
      .real("ny", [&e](std::size_t i) { return e.normals[i].y(); })
      .real("nz", [&e](std::size_t i) { return e.normals[i].z(); })
      .real("area", [&e, &frame](std::size_t i) { return e.areas[i] * frame.scale * frame.scale; })
      .real("distance", [&result, &frame](std::size_t i) { return frame.apply_length(result.envelope_distances[i]); });
  write_ply(out, "medax reconstruction: points on the envelope boundary, input frame", {vertex});
}

}  // namespace medax::evaluation
