// The `dey_zhao` stage as shipped: loaded from the built plugin, its declared parameters, its
// refusals, a pipeline run that writes the medial axis with its fields, and the shipped pipeline.
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

/// The dey_zhao stage of the built plugin.
struct Loaded : test::LoadedStage<ExtractionStage> {
  Loaded() : LoadedStage(MEDAX_DEY_ZHAO_PLUGIN, "dey_zhao") {}
};

}  // namespace

TEST_CASE("dey_zhao stage: declared parameters and package and docs", "[dey_zhao][stage]") {
  const Loaded loaded;
  const StageInfo& info = loaded.stage->info();
  CHECK(info.role == Role::Extraction);
  CHECK(info.doc == "docs/plugins/dey_zhao.md");
  CHECK(loaded.stage->package->name == "dey_zhao");
  std::map<std::string, const ParamSpec*> params;
  for (const ParamSpec& p : info.params) {
    params[p.name] = &p;
    CHECK(!p.doc.empty());
  }
  REQUIRE(params.size() == 9);
  CHECK(params.at("points")->default_text() == "auto");
  CHECK(std::get<double>(params.at("theta")->default_value) == Approx(3.14159265358979 / 8));
  CHECK(std::get<double>(params.at("rho")->default_value) == 8.0);
  CHECK(std::get<bool>(params.at("angle_condition")->default_value));
  CHECK(std::get<bool>(params.at("ratio_condition")->default_value));
  CHECK(params.at("inner")->default_text() == "auto");
  CHECK(params.at("inner")->choices ==
        std::vector<std::string>{"auto", "delaunay_surface", "mesh", "normals", "none"});
  CHECK(params.at("unbounded")->default_text() == "drop");
  CHECK(std::filesystem::exists(test::source_dir() / info.doc));
}

TEST_CASE("dey_zhao stage: extracts from samples or vertices and refuses what it cannot use", "[dey_zhao][stage]") {
  const Loaded loaded;
  Scene scene;
  scene.shape.mesh = testing::make_torus(1.0, 0.35, 96, 32);
  BasicContext ctx;

  const auto stage = loaded.create();
  REQUIRE_NOTHROW(stage->prepare(scene));
  const MedialComplex from_vertices = stage->extract(scene.shape, ctx);
  CHECK(from_vertices.generator_kind == "mesh_vertex");
  CHECK(!from_vertices.faces.empty());
  for (const auto& g : from_vertices.generators)
    for (Index i : g) CHECK(i < scene.shape.mesh.vertices.size());

  std::mt19937_64 rng(3);
  scene.shape.samples = services::sample_uniform(scene.shape.mesh, 3000, rng);
  const MedialComplex from_samples = stage->extract(scene.shape, ctx);  // auto: the samples
  CHECK(from_samples.generator_kind == "sample");
  CHECK(!from_samples.faces.empty());
  for (const char* name : {"p", "q", "polygon", "conditions", "unbounded"})
    CHECK(from_samples.face_props.labels.has(name));
  for (const char* name : {"angle", "ratio"}) CHECK(from_samples.face_props.fields.has(name));
  const auto vertices = loaded.create({{"points", std::string("vertices")}});
  CHECK(vertices->extract(scene.shape, ctx).generator_kind == "mesh_vertex");

  // Refusals, before any work.
  const auto both_off = loaded.create({{"angle_condition", false}, {"ratio_condition", false}});
  CHECK_THROWS_WITH(both_off->check_params(), Catch::Contains("both false"));
  const auto clip = loaded.create({{"unbounded", std::string("clip")}, {"clip_factor", 0.0}});
  CHECK_THROWS_WITH(clip->check_params(), Catch::Contains("clip_factor"));
  const auto samples = loaded.create({{"points", std::string("samples")}});
  Scene no_samples;
  no_samples.shape.mesh = scene.shape.mesh;
  CHECK_THROWS_WITH(samples->prepare(no_samples), Catch::Contains("sample") && Catch::Contains("stage"));
  const auto surface = loaded.create({{"inner", std::string("delaunay_surface")}});
  CHECK_THROWS_WITH(surface->prepare(scene), Catch::Contains("points: vertices"));
  Scene points_only;
  points_only.shape.samples = scene.shape.samples;
  const auto mesh_inner = loaded.create({{"inner", std::string("mesh")}});
  CHECK_THROWS_WITH(mesh_inner->prepare(points_only), Catch::Contains("mesh"));
  Scene empty;
  CHECK_THROWS_WITH(stage->prepare(empty), Catch::Contains("no surface mesh"));
  // Points only: auto uses the sample normals.
  const MedialComplex normals = stage->extract(points_only.shape, ctx);
  CHECK(!normals.faces.empty());
  // An open mesh cannot tell inside from outside.
  Shape open = scene.shape;
  open.mesh.faces.pop_back();
  CHECK_THROWS_WITH(mesh_inner->extract(open, ctx), Catch::Contains("not closed"));
}

TEST_CASE("dey_zhao stage in a pipeline writes the medial axis of a torus", "[dey_zhao][stage]") {
  Registry registry;
  REQUIRE(registry.load_file(MEDAX_DEY_ZHAO_PLUGIN));
  REQUIRE(registry.load_file(MEDAX_CONDITIONING_PLUGIN));
  const auto dir = test::scratch_dir("dey_zhao_pipeline");
  write_mesh(dir / "torus.off", testing::make_torus(2.0, 0.7, 128, 48));
  const RunResult result = test::run_yaml_text(dir,
                                               "name: dey_zhao\nseed: 0\ninput: torus.off\n"
                                               "stages:\n"
                                               "  - plugin: sample\n    params: {method: poisson, count: 6000}\n"
                                               "  - plugin: dey_zhao\n"
                                               "outputs: {medial: [ma, ply]}\n",
                                               registry);
  INFO(result.error);
  REQUIRE(result.ok);
  const MedialComplex m = read_ma(dir / "run" / "medial.ma");
  REQUIRE(m.num_vertices() > 100);
  std::vector<double> d;
  for (const Vec3& c : m.centres) d.push_back(testing::torus_axis_distance(c, 2.0));
  std::sort(d.begin(), d.end());
  CHECK(d[d.size() / 2] < 0.01);  // the core circle (tube radius 0.7)
  std::ifstream ply(dir / "run" / "medial.ply");
  const std::string text((std::istreambuf_iterator<char>(ply)), std::istreambuf_iterator<char>());
  for (const char* field : {"property double angle", "property double ratio", "property int p", "property int q"})
    CHECK(text.find(field) != std::string::npos);
  std::ifstream log(dir / "run" / "log.txt");
  const std::string log_text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  CHECK(log_text.find("[dey_zhao] time: Delaunay") != std::string::npos);
}

TEST_CASE("dey_zhao: the shipped pipelines validate", "[dey_zhao][stage]") {
  Registry registry;
  registry.load_default();
  if (!registry.find("counts") || !registry.find("sample") || !registry.find("dey_zhao")) {
    WARN("evaluation or conditioning plugins not built: pipelines/dey_zhao.yaml not validated");
    return;
  }
  CHECK_NOTHROW(load_pipeline(test::source_dir() / "pipelines" / "dey_zhao.yaml", registry));
}
