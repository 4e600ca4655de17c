// The three stages: normalize (unit bounding box, centred), repair (check, fix the cheap problems,
// refuse or repair the rest), sample (oriented samples with areas, seeded).
#include "stages.hpp"

#include "repair_policy.hpp"

#include <medax/services/poisson.hpp>
#include <medax/services/sampling.hpp>

#include <sstream>
#include <stdexcept>

namespace medax::conditioning {

// ---- normalize -------------------------------------------------------------------------------

StageInfo NormalizeStage::describe() {
  return {"normalize",
          "Centres the shape at its bounding-box centre and scales it to a unit diagonal or longest side",
          "docs/plugins/conditioning.md#normalize"};
}

void NormalizeStage::declare(ParamBinder& p) {
  p.add("mode", mode_, kNormalizeModes, "what becomes 1: the bounding-box diagonal or its longest side");
}

void NormalizeStage::check_scene(const Scene& scene) const { compute_normalization(scene.shape, mode_); }

void NormalizeStage::condition(Shape& shape, Context& ctx) {
  const Normalization n = compute_normalization(shape, mode_);
  apply_normalization(shape, n);
  std::ostringstream log;
  log.precision(10);
  log << "scaled by 1/" << n.size << " about (" << n.centre.x() << ", " << n.centre.y() << ", " << n.centre.z()
      << "); outputs map back to the input frame";
  ctx.info(log.str());
}

// ---- repair ----------------------------------------------------------------------------------

StageInfo RepairStage::describe() {
  return {"repair",
          "Checks the mesh (closed, manifold, outward, no self-intersection), fixes cheap problems, "
          "refuses or repairs the rest",
          "docs/plugins/conditioning.md#repair"};
}

void RepairStage::declare(ParamBinder& p) {
  p.add("repair", repair_all_,
        "repair holes and self-intersections too (sets fill_holes and remove_self_intersections); refuses when "
        "that fails");
  p.add("fill_holes", options_.fill_holes, "close boundary loops (CGAL triangulate_refine_and_fair_hole)");
  p.add("fair_holes", options_.fair_holes, "fair the hole patches (smooth); false: flat refined patches");
  p.add("max_hole_edges", options_.max_hole_edges, "leave holes with more boundary edges open (and refuse); 0: no limit").at_least(0);
  p.add("remove_self_intersections", options_.remove_self_intersections,
        "remove self-intersections (CGAL autorefinement, then local repair); refuses when that fails or changes "
        "the shape");
  p.add("check_self_intersections", options_.check_self_intersections,
        "test for self-intersections (the slow check, about 0.2 s per 100k faces); false: blind to them (warns), "
        "and remove_self_intersections is refused");
}

services::RepairOptions RepairStage::repair_options() const {
  services::RepairOptions o = options_;
  o.fill_holes = repair_all_ || o.fill_holes;
  o.remove_self_intersections = repair_all_ || o.remove_self_intersections;
  return o;
}

void RepairStage::check_params() const {
  const services::RepairOptions o = repair_options();
  if (o.remove_self_intersections && !o.check_self_intersections)
    throw std::invalid_argument(
        "remove_self_intersections needs check_self_intersections: true (the result must be checked)");
}

void RepairStage::check_scene(const Scene& scene) const {
  if (scene.shape.mesh.empty())
    throw std::invalid_argument("the shape has no surface mesh (repair works on meshes, not samples; "
                                "`reconstruct_mesh` makes one of a point cloud: docs/plugins/pointset.md)");
  check_params();  // for direct calls; a pipeline has checked them when it was validated
}

void RepairStage::condition(Shape& shape, Context& ctx) {
  const services::RepairOptions options = repair_options();
  const services::RepairResult result = services::repair_mesh(shape.mesh, options);
  ctx.info("input: " + result.before.summary());
  for (const std::string& action : result.actions) ctx.info(action);
  const RepairDecision decision = decide_repair(result, options, shape.source);
  if (!decision.accept) throw std::runtime_error(decision.refusal);
  for (const std::string& warning : decision.warnings) ctx.warn(warning);
  if (!result.changed) {
    ctx.info("the mesh is valid as it is");
    return;
  }
  ctx.info("repaired: " + result.after.summary());
  shape.mesh = result.mesh;
  if (!shape.samples.empty()) {
    ctx.warn("dropped the samples taken before repair (they may no longer lie on the surface); "
             "put `sample` after `repair`");
    shape.samples = {};
  }
}

// ---- sample ----------------------------------------------------------------------------------

StageInfo SampleStage::describe() {
  return {"sample",
          "Oriented surface samples with areas: uniform, Poisson-disk (blue noise) or the mesh vertices",
          "docs/plugins/conditioning.md#sample"};
}

void SampleStage::declare(ParamBinder& p) {
  p.add("method", settings_.method, kSampleMethods,
        "poisson: blue noise by sample elimination (or dart throwing with min_distance); uniform: area-weighted "
        "random; vertices: the mesh vertices");
  p.add("count", settings_.count, "number of samples (uniform; poisson unless min_distance > 0; ignored by vertices)")
      .at_least(1);
  p.add("min_distance", settings_.min_distance,
        "poisson: sample by this minimum distance instead of by count; 0: by count")
      .at_least(0)
      .in_unit("current frame length");
  p.add("oversampling", settings_.poisson.oversampling, "poisson: uniform candidates drawn per sample").range(1, 100);
  p.add("candidates", settings_.poisson.candidates, kPoissonCandidates,
        "poisson by count: what the elimination starts from: uniform (Yuksel's); darts: the uniform candidates "
        "thinned first by parallel dart throwing at 0.65 spacings (about 3x faster at 1M, other samples)");
  p.add("normal_angle", settings_.poisson.normal_angle_deg,
        "poisson: samples whose normals differ by this much never repel (the two sides of a thin plate are "
        "sampled independently)")
      .range(0, 180)
      .in_unit("degrees");
}

void SampleStage::check_scene(const Scene& scene) const {
  if (scene.shape.mesh.empty())
    throw std::invalid_argument("the shape has no surface mesh to sample (a point cloud is samples already; "
                                "`reconstruct_mesh` makes a mesh of it: docs/plugins/pointset.md)");
}

void SampleStage::condition(Shape& shape, Context& ctx) {
  shape.samples = sample_surface(shape.mesh, settings_, ctx.rng(), [&ctx](double fraction, std::string_view phase) {
    ctx.check_cancelled();
    ctx.progress(fraction, phase);
  });
  std::ostringstream log;
  log.precision(4);
  log << "took " << shape.samples.size() << " samples (" << choice_name(kSampleMethods, settings_.method);
  if (settings_.method == SampleMethod::Poisson && settings_.min_distance == 0 &&
      settings_.poisson.candidates == services::PoissonCandidates::Darts)
    log << ", from dart-thrown candidates";
  log << ")";
  if (settings_.method == SampleMethod::Poisson) {
    const double spacing = services::poisson_packing_distance(services::surface_area(shape.mesh), shape.samples.size());
    const double d = services::min_sample_distance(shape.samples, settings_.poisson.normal_angle_deg);
    log << "; minimum distance " << d << " = " << d / spacing << " of the hexagonal-packing spacing";
  }
  ctx.info(log.str());
}

}  // namespace medax::conditioning
