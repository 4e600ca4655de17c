// sample: oriented surface samples with areas (uniform, Poisson-disk or the vertices), seeded.
#include "stages.hpp"
#include "surface_sampling.hpp"

#include <medax/services/poisson.hpp>
#include <medax/services/sampling.hpp>

#include <sstream>
#include <stdexcept>

namespace medax::conditioning {

StageInfo SampleStage::describe() {
  return {"sample",
          "Oriented surface samples with areas: uniform, Poisson-disk (blue noise) or the mesh vertices",
          "docs/plugins/conditioning.md#sample",
          {ParamSpec::choice("method", "poisson", {"poisson", "uniform", "vertices"},
                             "poisson: blue noise by sample elimination (or dart throwing with min_distance); "
                             "uniform: area-weighted random; vertices: the mesh vertices"),
           ParamSpec::integer("count", 10000, "number of samples (uniform; poisson unless min_distance > 0)").at_least(1),
           ParamSpec::real("min_distance", 0.0,
                           "poisson: sample by this minimum distance instead of by count; 0: by count")
               .at_least(0)
               .in_unit("current frame length"),
           ParamSpec::real("oversampling", 5.0, "poisson: uniform candidates drawn per sample").range(1, 100),
           ParamSpec::real("normal_angle", 120.0,
                           "poisson: samples whose normals differ by this much never repel (the two sides of "
                           "a thin plate are sampled independently)")
               .range(0, 180)
               .in_unit("degrees")}};
}

namespace {
SampleSettings settings_from(const ParamSet& params) {
  SampleSettings s;
  s.method = parse_sample_method(params.text("method"));
  s.count = static_cast<std::size_t>(params.integer("count"));
  s.min_distance = params.real("min_distance");
  s.oversampling = params.real("oversampling");
  s.normal_angle_deg = params.real("normal_angle");
  return s;
}
}  // namespace

void SampleStage::prepare(const Scene& scene) const {
  settings_from(params());
  if (scene.shape.mesh.empty())
    throw std::invalid_argument("sample: the shape has no surface mesh to sample");
}

void SampleStage::condition(Shape& shape, Context& ctx) {
  const SampleSettings settings = settings_from(params());
  shape.samples = sample_surface(shape.mesh, settings, ctx.rng());
  std::ostringstream log;
  log.precision(4);
  log << "took " << shape.samples.size() << " samples (" << params().text("method") << ")";
  if (settings.method == SampleMethod::Poisson) {
    const double spacing = services::poisson_packing_distance(services::surface_area(shape.mesh), shape.samples.size());
    const double d = services::min_sample_distance(shape.samples, settings.normal_angle_deg);
    log << "; minimum distance " << d << " = " << d / spacing << " of the hexagonal-packing spacing";
  }
  ctx.info(log.str());
}

}  // namespace medax::conditioning
