// The coverage_axis stage on a real mesh after the interior Voronoi axis: the selection covers the
// samples, exactly |selection| distinct vertices are marked, the run is deterministic; and the
// stage as loaded from the built plugin.
#include "interior_voronoi.hpp"
#include "loaded_stage.hpp"
#include "stages.hpp"

#include <medax/io.hpp>

#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <numeric>

using namespace medax;
using namespace medax::coverage_axis;

namespace {

struct Run {
  Selection selection;
  std::vector<int> selected;
  MedialComplex medial;
};

Scene voronoi_scene(const std::string& mesh) {
  Scene scene;
  scene.shape.mesh = read_mesh(test::data_dir() / mesh);
  scene.medial = voronoi::interior_voronoi(scene.shape.mesh.vertices, scene.shape.mesh);
  return scene;
}

Run run_stage(Scene scene, const ParamSet& params, std::uint64_t seed = 1) {
  CoverageAxisStage stage;
  stage.configure(params);
  stage.prepare(scene);
  BasicContext ctx(seed, false, "coverage_axis");
  stage.measure(scene.shape, *scene.medial, ctx);
  return {ctx.data().get(kSelection), scene.medial->get(kSelected), *scene.medial};
}

ParamSet small(const std::string& mode, const std::string& candidates) {
  ParamSet p;
  p.set("mode", std::string(mode));
  p.set("candidates", candidates);
  p.set("samples", 400LL);
  p.set("candidate_count", 3000LL);
  p.set("dilation", 0.05);
  return p;
}

void check_covered_and_marked(const Run& run, const Shape& shape) {
  const Selection& s = run.selection;
  CHECK(s.objective == s.centres.size());
  CHECK(s.objective > 0);
  // Exactly |selection| vertices marked, one per sphere (as long as the complex has enough).
  CHECK(std::accumulate(run.selected.begin(), run.selected.end(), std::size_t(0)) == s.objective);
  CHECK(s.marked == s.objective);
  // Every sample some candidate covers is covered by a selected dilated sphere.
  std::size_t uncovered = 0;
  for (const Vec3& p : s.sample_points) {
    bool covered = false;
    for (std::size_t i = 0; i < s.centres.size(); ++i)
      covered = covered || (p - s.centres[i]).norm() < s.radii[i] + s.dilation;
    uncovered += covered ? 0 : 1;
  }
  CHECK(uncovered == s.uncovered);
  CHECK(s.sample_points.size() == s.samples);
  (void)shape;
}

}  // namespace

TEST_CASE("coverage_axis stage: exact and greedy on the ellipsoid's Voronoi axis", "[coverage_axis][stage]") {
  const Scene scene = voronoi_scene("ellipsoid.off");
  SECTION("exact, random candidates") {
    const Run run = run_stage(scene, small("exact", "random"));
    check_covered_and_marked(run, scene.shape);
    CHECK(run.selection.uncovered == 0);
    CHECK(run.selection.proven_optimal);
    CHECK(run.selection.lp_bound <= run.selection.objective + 1e-6);
    const Run greedy = run_stage(scene, small("greedy", "random"));
    check_covered_and_marked(greedy, scene.shape);
    CHECK(greedy.selection.objective >= run.selection.objective);  // same samples and candidates
  }
  SECTION("exact, Voronoi candidates") {
    const Run run = run_stage(scene, small("exact", "voronoi"));
    check_covered_and_marked(run, scene.shape);
    // A Voronoi candidate snaps to its own vertex.
    for (std::size_t i = 0; i < run.selection.centres.size(); ++i) {
      bool own = false;
      for (Index v = 0; v < run.medial.num_vertices(); ++v)
        own = own || (run.selected[v] && run.medial.centres[v] == run.selection.centres[i]);
      CHECK(own);
    }
  }
}

TEST_CASE("coverage_axis stage: deterministic for a seed", "[coverage_axis][stage]") {
  const Scene scene = voronoi_scene("joint.off");
  const Run a = run_stage(scene, small("exact", "random"), 4);
  const Run b = run_stage(scene, small("exact", "random"), 4);
  CHECK(a.selection.centres == b.selection.centres);
  CHECK(a.selection.radii == b.selection.radii);
  CHECK(a.selected == b.selected);
  check_covered_and_marked(a, scene.shape);
}

TEST_CASE("coverage_axis stage: as loaded from the plugin, with its docs page", "[coverage_axis][stage]") {
  const test::LoadedStage<SignificanceStage> loaded(MEDAX_COVERAGE_AXIS_PLUGIN, "coverage_axis");
  const StageInfo& info = loaded.stage->info();
  CHECK(info.role == Role::Significance);
  CHECK(std::filesystem::exists(test::source_dir() / info.doc));
  std::map<std::string, std::string> defaults;
  for (const ParamSpec& p : info.params) {
    defaults[p.name] = p.default_text();
    CHECK(!p.doc.empty());
  }
  CHECK(defaults.at("samples") == "1500");
  CHECK(defaults.at("candidate_count") == "20000");
  CHECK(defaults.at("mode") == "exact");
  ParamSet wrong;
  wrong.set("target", 10LL);
  const auto stage = loaded.create();
  stage->configure(wrong);
  CHECK_THROWS_WITH(stage->check_params(), Catch::Contains("mode: greedy"));
}
