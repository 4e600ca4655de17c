// The shipped point-cloud pipelines on the scan-like torus cloud of data/torus_scan.xyz (no
// normals, noise, a hole, stray points): validated against the built plugins, then run stage by
// stage on the shape read_shape() gives (the runner's own read of the input is the kernel's).
#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>

#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace medax;

namespace {

/// Runs every stage of `config` on the shape of its input, as the runner does.
Scene run_stages(const PipelineConfig& config) {
  Scene scene;
  scene.shape = read_shape(config.input);
  for (const StageConfig& stage : config.stages) {
    INFO(stage.id);
    stage.instance->prepare(scene);
    BasicContext ctx(config.seed, false, stage.id);
    stage.instance->run(scene, ctx);
  }
  return scene;
}

/// Median distance of the complex's centres, in the input frame, to the torus's core circle.
double median_core_distance(const Scene& scene) {
  std::vector<double> d;
  for (const Vec3& c : scene.medial->centres) d.push_back(testing::torus_axis_distance(scene.shape.to_input.apply(c), 1.0));
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

const Registry* shipped_registry() {
  static Registry* registry = [] {
    auto* r = new Registry();  // kept for the process: the stages' code lives in its plugins
    r->load_default();
    return r;
  }();
  for (const char* stage : {"outliers", "normalize", "vmas", "vmas_dual", "dey_zhao", "counts", "topology"})
    if (!registry->find(stage)) return nullptr;
  return registry;
}

std::filesystem::path pipeline(const std::string& name) { return test::source_dir() / "pipelines" / name; }

}  // namespace

TEST_CASE("pointcloud_vmas on a raw torus scan: the core circle with its one cycle", "[pointset][pipelines]") {
  const Registry* registry = shipped_registry();
  if (!registry) {
    WARN("the conditioning, vmas, dey_zhao or evaluation plugins are not built: pipelines not run");
    return;
  }
  const PipelineConfig config = load_pipeline(pipeline("pointcloud_vmas.yaml"), *registry);
  REQUIRE(is_point_set_file(config.input));
  const Scene scene = run_stages(config);
  REQUIRE(scene.medial);
  CHECK(scene.medial->num_vertices() == 30);
  const services::ComplexTopology top = services::complex_topology(*scene.medial);
  CHECK(top.b0 == 1);
  CHECK(top.b1 == 1);
  CHECK(median_core_distance(scene) < 0.05);
}

TEST_CASE("pointcloud_dey_zhao on a raw torus scan: facets around the core circle", "[pointset][pipelines]") {
  const Registry* registry = shipped_registry();
  if (!registry) {
    WARN("the conditioning, vmas, dey_zhao or evaluation plugins are not built: pipelines not run");
    return;
  }
  const PipelineConfig config = load_pipeline(pipeline("pointcloud_dey_zhao.yaml"), *registry);
  const Scene scene = run_stages(config);
  REQUIRE(scene.medial);
  CHECK(scene.medial->faces.size() > 100);
  CHECK(median_core_distance(scene) < 0.05);
  CHECK(services::complex_topology(*scene.medial).b1 >= 1);  // around the hole of the torus
}

TEST_CASE("a mesh through a point-cloud pipeline is refused naming what the stage works on",
          "[pointset][pipelines]") {
  const Registry* registry = shipped_registry();
  if (!registry) return;
  Overrides overrides;
  overrides.input = test::data_dir() / "cube.off";
  const PipelineConfig config = load_pipeline(pipeline("pointcloud_vmas.yaml"), *registry, overrides);
  CHECK_THROWS_WITH(run_stages(config), Catch::Contains("the shape has no points"));
}
