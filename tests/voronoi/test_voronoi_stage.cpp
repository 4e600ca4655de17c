// The `voronoi` stage as shipped: loaded from the built plugin, its declared parameters, its
// refusals, and a pipeline run that writes the medial axis.
#include "loaded_stage.hpp"
#include "pipeline_run.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>

#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <fstream>

using namespace medax;

namespace {

/// The voronoi stage of the built plugin.
struct Loaded : test::LoadedStage<ExtractionStage> {
  Loaded() : LoadedStage(MEDAX_VORONOI_PLUGIN, "voronoi") {}
};

}  // namespace

TEST_CASE("voronoi stage: declared parameters, package and docs", "[voronoi][stage]") {
  const Loaded loaded;
  const StageInfo& info = loaded.stage->info();
  CHECK(info.role == Role::Extraction);
  CHECK(info.doc == "docs/plugins/voronoi.md");
  CHECK(loaded.stage->package->name == "voronoi");
  std::map<std::string, const ParamSpec*> params;
  for (const ParamSpec& p : info.params) {
    params[p.name] = &p;
    CHECK(!p.doc.empty());
  }
  REQUIRE(params.size() == 3);
  CHECK(params.at("points")->default_text() == "vertices");
  CHECK(params.at("points")->choices == std::vector<std::string>{"vertices", "samples"});
  CHECK(params.at("connectivity")->default_text() == "faces");
  CHECK(params.at("inside_test")->default_text() == "ray_grid");
  CHECK(std::filesystem::exists(test::source_dir() / info.doc));
}

TEST_CASE("voronoi stage: extracts from vertices or samples, and refuses what it cannot use",
          "[voronoi][stage]") {
  const Loaded loaded;
  Shape shape;
  shape.mesh = testing::make_capsule(0.5, 1.0, 24);
  BasicContext ctx;

  const auto vertices = loaded.create();
  Scene scene;
  scene.shape = shape;
  REQUIRE_NOTHROW(vertices->prepare(scene));
  const MedialComplex m = vertices->extract(shape, ctx);
  CHECK(m.num_vertices() > 100);
  CHECK(m.generator_kind == "mesh_vertex");
  CHECK(!m.faces.empty());

  const auto samples = loaded.create({{"points", std::string("samples")}, {"connectivity", std::string("edges")}});
  CHECK_THROWS_WITH(samples->prepare(scene), Catch::Contains("sample") && Catch::Contains("stage"));
  CHECK_THROWS_AS(samples->extract(shape, ctx), std::invalid_argument);
  std::mt19937_64 rng(3);
  scene.shape.samples = services::sample_uniform(shape.mesh, 1500, rng);
  REQUIRE_NOTHROW(samples->prepare(scene));
  const MedialComplex s = samples->extract(scene.shape, ctx);
  CHECK(s.generator_kind == "sample");
  CHECK(s.faces.empty());
  CHECK(!s.edges.empty());
  for (const auto& g : s.generators)
    for (Index i : g) CHECK(i < scene.shape.samples.size());

  Scene samples_only;
  samples_only.shape.samples = scene.shape.samples;
  CHECK_THROWS_WITH(samples->prepare(samples_only), Catch::Contains("mesh"));
  CHECK_THROWS_WITH(samples->extract(samples_only.shape, ctx), Catch::Contains("mesh"));
  Scene empty;
  CHECK_THROWS_WITH(vertices->prepare(empty), Catch::Contains("mesh"));

  Shape open = shape;
  open.mesh.faces.pop_back();
  // The stage does not name itself (the runner prefixes its id).
  CHECK_THROWS_WITH(vertices->extract(open, ctx), !Catch::Contains("voronoi:") && Catch::Contains("not closed") &&
                                                      Catch::Contains("repair"));
}

TEST_CASE("voronoi stage in a pipeline writes the medial axis of a sphere", "[voronoi][stage]") {
  const Loaded loaded;
  const auto dir = test::scratch_dir("voronoi_pipeline");
  write_mesh(dir / "sphere.off", testing::make_sphere(2.0, 2));
  const RunResult result = test::run_yaml_text(dir,
                                               "name: voronoi\nseed: 0\ninput: sphere.off\n"
                                               "stages:\n"
                                               "  - plugin: voronoi\n    params: {connectivity: faces}\n"
                                               "outputs: {medial: [ma, ply]}\n",
                                               loaded.registry);
  INFO(result.error);
  REQUIRE(result.ok);
  const MedialComplex m = read_ma(dir / "run" / "medial.ma");
  REQUIRE(m.num_vertices() > 0);
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    CHECK(m.centres[i].norm() < 1e-6);
    CHECK(m.radii[i] == Approx(2.0).epsilon(1e-6));
  }
  CHECK(std::filesystem::exists(dir / "run" / "medial.ply"));
}
