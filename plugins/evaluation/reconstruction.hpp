#pragma once
// Reconstruction error of a medial complex: distances between the input surface S and the
// boundary of the complex's sphere/cone/slab envelope E (docs/plugins/evaluation.md).
#include <medax/metrics.hpp>
#include <medax/services/envelope.hpp>
#include <medax/surface.hpp>

#include <functional>
#include <iosfwd>
#include <memory>
#include <random>
#include <string_view>

namespace medax::services {
class SurfaceDistance;
class PointIndex;
}  // namespace medax::services

namespace medax::evaluation {

struct ReconstructionOptions {
  int resolution = 150;             ///< envelope grid step = smallest bbox side / resolution
  double step = 0;                  ///< absolute grid step; 0 = from `resolution`
  bool use_vertices = true;         ///< surface samples include the mesh vertices
  std::size_t uniform_samples = 0;  ///< plus this many area-uniform surface samples
  /// Budget of envelope boundary points (issue 16): when the surface's area would give more
  /// points than this at the step from `resolution` (about 1.5 × area / step²), the step is
  /// enlarged to fit, which bounds the cost on slender shapes. 0: no budget, the VMAS rule
  /// alone (the sampling before issue 16, e.g. for VMAS's Table 1). An explicit `step` is
  /// always used as given.
  std::size_t max_envelope_samples = 20'000;
};

struct ReconstructionResult {
  double diagonal = 0;  ///< bbox diagonal of the input surface (the % normaliser)
  double step = 0;      ///< envelope grid step used
  double requested_step = 0;  ///< the step the options asked for (larger `step` = capped)
  std::size_t primitives = 0, surface_samples = 0;
  double surface_inside_fraction = 0;  ///< fraction of surface samples strictly inside E
  double surface_to_envelope_max = 0, surface_to_envelope_mean = 0;  ///< over surface samples
  double envelope_to_surface_max = 0, envelope_to_surface_mean = 0;  ///< over ∂E, by area
  double envelope_area = 0;
  services::EnvelopeSamples envelope;       ///< the points of ∂E used
  std::vector<double> envelope_distances;   ///< their distances to S

  double hausdorff() const { return std::max(surface_to_envelope_max, envelope_to_surface_max); }
  double eps1() const { return surface_to_envelope_mean; }  ///< MSD ε̄¹
  double eps2() const { return envelope_to_surface_mean; }  ///< MSD ε̄²
  double eps() const { return std::max(eps1(), eps2()); }   ///< MSD ε̄ (two-sided)
  Metrics metrics() const;
};

using Progress = std::function<void(double, std::string_view)>;

/// Diagonal of the bounding box of the shape's mesh vertices (or, without a mesh, its samples).
double shape_diagonal(const Shape& shape);

/// The points measured from the shape's side: the mesh vertices that faces use (`use_vertices`)
/// and `uniform_samples` area-uniform points; without a mesh, the shape's samples.
std::vector<Vec3> shape_samples(const Shape& shape, const ReconstructionOptions& options, std::mt19937_64& rng);

/// Unsigned distances to a shape: to its mesh (CGAL AABB tree), or without a mesh to the nearest
/// sample. Built once (the tree is the costly part), so that it can be built beside other work.
class ShapeDistance {
 public:
  explicit ShapeDistance(const Shape& shape);
  ~ShapeDistance();
  /// The distance of each point, in blocks, with `cancel` polled between them.
  std::vector<double> distances(const std::vector<Vec3>& points, const services::CancelCheck& cancel = {}) const;

 private:
  std::unique_ptr<services::SurfaceDistance> mesh_;
  std::unique_ptr<services::PointIndex> samples_;
};

/// ShapeDistance(shape).distances(points, cancel).
std::vector<double> distances_to_shape(const Shape& shape, const std::vector<Vec3>& points,
                                       const services::CancelCheck& cancel = {});

/// Adds `name` = value and `name_pct` = 100 · value / diagonal.
void add_distance(Metrics& m, const std::string& name, double value, double diagonal);

/// Measures `medial` against the shape's mesh (or, without a mesh, its samples as a point
/// cloud). Throws std::invalid_argument when there is nothing to measure. `cancel` (optional) is
/// polled from the worker threads every few hundred points; what it throws stops the measure.
ReconstructionResult measure_reconstruction(const Shape& shape, const MedialComplex& medial,
                                            const ReconstructionOptions& options, std::mt19937_64& rng,
                                            const Progress& progress = {}, const services::CancelCheck& cancel = {});

/// Writes the envelope's boundary points as an ASCII PLY vertex element: x y z, nx ny nz, area and
/// distance to the surface, mapped by `frame` (the shape's map to the input's frame). Reals are
/// written in the shortest form that reads back exactly (medax/ply.hpp).
void write_envelope_ply(std::ostream& out, const ReconstructionResult& result, const Similarity& frame);

/// The grid step `options` give for this shape and envelope (see ReconstructionOptions).
double envelope_step(const Shape& shape, const services::Envelope& envelope, const ReconstructionOptions& options);

}  // namespace medax::evaluation
