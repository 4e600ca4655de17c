#include "stages.hpp"

#include "correction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace medax::qmat {

StageInfo QmatStage::describe() {
  return {"qmat",
          "Q-MAT: edge collapse of the medial complex by slab quadric error and stability ratio (Li et al. 2015)",
          "docs/plugins/qmat.md"};
}

void QmatStage::declare(ParamBinder& p) {
  p.add("target_vertices", options_.target_vertices,
        "stop at this many vertices; 0 = the number of saved vertices when there are some (VMAS protocol), "
        "else no count target (then max_cost must be set)")
      .at_least(0);
  p.add("max_cost", options_.max_cost,
        "stop before a collapse whose priority (E + k)·γ² exceeds this, in units of the surface bbox diagonal "
        "squared; 0 = no bound")
      .at_least(0);
  p.add("stability_weight", options_.stability_weight, "k in the priority (E + k)·γ² (authors: 1e-5)").at_least(0);
  p.add("boundary_weight", options_.boundary_weight,
        "β of the sheet-boundary planes, weighted 0.1·β·γ² (authors' code: 0.1)")
      .at_least(0);
  p.add("cone_terms", options_.cone_terms, {{"qmat_code", ConeTerms::QmatCode}, {"clean", ConeTerms::Clean}},
        "planes added for faceless edges: the authors' pseudo-slab (c₀ + c₁ third sphere), or the cone's "
        "tangent planes in four directions 90° apart");
  p.add("flip_test", options_.flip_test,
        "refuse an optimal sphere that flips an incident face (the intended test; the authors' is inverted)");
  p.add("topology_guard", options_.topology_guard,
        "QMAT's guard: keep edges of unfilled 3-cycles (holes) and edges to curve tips");
  p.add("guard_below", options_.guard_below, "the guard acts once this few vertices remain (authors: 100)")
      .at_least(0);
  p.add("link_condition", options_.link_condition,
        "collapse only edges that satisfy the link condition (keeps the homotopy type; off in the authors' code)");
  p.add("keep", keep_, {{"auto", Keep::Auto}, {"none", Keep::None}, {"selected", Keep::Selected}},
        "saved vertices that never move: those with a nonzero int vertex column `selected` (auto: when the "
        "column exists)");
  p.add("stale_saved_costs", options_.stale_saved_costs,
        "parity with the authors' connection program: cost the queue before marking saved vertices (a stale "
        "entry can then move a saved vertex once)");
  p.add("correct_spheres", correct_spheres_,
        "after simplifying, replace each sphere by the shrinking ball from its closest surface point (VMAS §4 "
        "correction of the baselines); needs the surface mesh");
}

void QmatStage::check_scene(const Scene& scene) const {
  if (keep_ == Keep::Selected && scene.medial && !scene.medial->has(kSelected))
    throw std::invalid_argument("`keep: selected` but the medial complex has no int vertex column `selected`; "
                                "run a stage that selects spheres (coverage_axis) first, or use `keep: auto`");
  if (correct_spheres_ && scene.shape.mesh.empty())
    throw std::invalid_argument("`correct_spheres: true` needs the surface mesh, and the shape has none; "
                                "set `correct_spheres: false`");
}

std::vector<char> QmatStage::saved_flags(const MedialComplex& medial) const {
  if (keep_ == Keep::None || !medial.has(kSelected)) return {};
  const std::vector<int>& selected = medial.get(kSelected);
  std::vector<char> saved(selected.size());
  std::transform(selected.begin(), selected.end(), saved.begin(), [](int s) { return s != 0 ? 1 : 0; });
  return saved;
}

std::size_t QmatStage::target(std::size_t saved) const {
  if (options_.target_vertices > 0) return options_.target_vertices;
  if (saved > 0) return saved;
  if (options_.max_cost > 0) return 0;
  throw std::invalid_argument("nothing says when to stop: target_vertices is 0, no vertex is saved and max_cost "
                              "is 0; set target_vertices (or max_cost)");
}

void QmatStage::simplify(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const std::vector<char> saved = saved_flags(medial);
  QmatOptions options = options_;
  const std::size_t saved_count = static_cast<std::size_t>(std::count(saved.begin(), saved.end(), 1));
  options.target_vertices = target(saved_count);
  // QMAT's unit: the surface bbox diagonal (its thresholds live there); without a mesh, the balls'.
  if (!shape.mesh.empty()) options.unit_length = bbox_diagonal(shape.mesh.vertices);
  QmatReport report;
  medial = qmat::simplify(medial, saved, options, &report,
                          [&ctx](double f) {
                            ctx.check_cancelled();
                            ctx.progress(std::min(1.0, f), "collapsing edges");
                          });
  ctx.info(fmt::format("{} -> {} vertices ({} collapses, {} saved, target {}); stopped by {}; last priority {:.3g}",
                       report.initial_vertices, report.final_vertices, report.collapses, report.saved,
                       options.target_vertices, report.stopped_by, report.last_cost));
  ctx.info(fmt::format("{} faces without slab planes; {} collapses refused by the topology checks; time: setup "
                       "{:.3f} s, collapse {:.3f} s",
                       report.invalid_faces, report.dropped, report.seconds_setup, report.seconds_collapse));
  if (report.stopped_by == "queue" && options.target_vertices > 0)
    ctx.warn(fmt::format("the queue ran out at {} vertices, above the target {}", report.final_vertices,
                         options.target_vertices));
  if (!correct_spheres_) return;
  const CorrectionReport c = shrinking_ball_correction(medial, shape.mesh);
  ctx.info(fmt::format("shrinking-ball correction: {} spheres replaced, {} kept (no second contact), largest "
                       "change {:.4g}",
                       c.corrected, c.kept, c.max_shift));
}

}  // namespace medax::qmat
