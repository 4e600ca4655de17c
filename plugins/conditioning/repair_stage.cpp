// repair: checks the mesh; fixes duplicates, degenerate faces and orientation; refuses holes,
// non-manifold parts and self-intersections unless asked to repair them.
#include "repair_policy.hpp"
#include "stages.hpp"

#include <medax/services/mesh_check.hpp>

#include <stdexcept>

namespace medax::conditioning {

StageInfo RepairStage::describe() {
  return {"repair",
          "Checks the mesh (closed, manifold, outward, no self-intersection), fixes cheap problems, "
          "refuses or repairs the rest",
          "docs/plugins/conditioning.md#repair",
          {ParamSpec::boolean("repair", false,
                              "repair holes and self-intersections too (sets fill_holes and "
                              "remove_self_intersections); refuses when that fails"),
           ParamSpec::boolean("fill_holes", false, "close boundary loops (CGAL triangulate_refine_and_fair_hole)"),
           ParamSpec::boolean("fair_holes", true, "fair the hole patches (smooth); false: flat refined patches"),
           ParamSpec::integer("max_hole_edges", 0, "leave larger holes open (and refuse); 0: no limit").at_least(0),
           ParamSpec::boolean("remove_self_intersections", false,
                              "remove self-intersections (CGAL autorefinement, then local repair); "
                              "refuses when that fails or changes the shape"),
           ParamSpec::boolean("check_self_intersections", true,
                              "test for self-intersections (the slow check, about 0.2 s per 100k faces)")}};
}

namespace {
services::RepairOptions options_from(const ParamSet& params) {
  services::RepairOptions o;
  const bool all = params.boolean("repair");
  o.fill_holes = all || params.boolean("fill_holes");
  o.fair_holes = params.boolean("fair_holes");
  o.max_hole_edges = static_cast<std::size_t>(params.integer("max_hole_edges"));
  o.remove_self_intersections = all || params.boolean("remove_self_intersections");
  o.check_self_intersections = params.boolean("check_self_intersections");
  return o;
}
}  // namespace

void RepairStage::prepare(const Scene& scene) const {
  if (scene.shape.mesh.empty())
    throw std::invalid_argument("repair: the shape has no surface mesh (repair works on meshes, not samples)");
  const auto o = options_from(params());
  if (o.remove_self_intersections && !o.check_self_intersections)
    throw std::invalid_argument(
        "repair: remove_self_intersections needs check_self_intersections: true (the result must be checked)");
}

void RepairStage::condition(Shape& shape, Context& ctx) {
  const services::RepairOptions options = options_from(params());
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

}  // namespace medax::conditioning
