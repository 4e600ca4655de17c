// The shipped point-cloud pipelines on the scan-like torus cloud of data/torus_scan.xyz (no
// normals, noise, a hole, stray points), run by the runner as `medax run` does: it reads the
// .xyz input as a point cloud; the run folder's medial.ma is checked against the torus.
#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/sweep.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>

#include <pipeline_run.hpp>
#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace medax;

namespace {

/// Median distance of the complex's centres (the run folder's, in the input frame) to the torus's core circle.
double median_core_distance(const MedialComplex& medial) {
  std::vector<double> d;
  for (const Vec3& c : medial.centres) d.push_back(testing::torus_axis_distance(c, 1.0));
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

/// The shipped plugins (built before this test: tests/pointset/CMakeLists.txt).
const Registry& shipped_registry() {
  static Registry* registry = [] {
    auto* r = new Registry();  // kept for the process: the stages' code lives in its plugins
    r->load_default();
    return r;
  }();
  return *registry;
}

std::filesystem::path pipeline(const std::string& name) { return test::source_dir() / "pipelines" / name; }

/// Runs a shipped pipeline on its default input; the medial complex it wrote.
MedialComplex run_shipped(const std::string& name) {
  const auto out = test::scratch_dir("pointcloud_" + name) / "run";
  const RunResult result = test::run_quietly(pipeline(name + ".yaml"), shipped_registry(), out);
  INFO(result.error);
  REQUIRE(result.ok);
  return read_ma(out / "medial.ma");
}

}  // namespace

TEST_CASE("pointcloud_vmas on a raw torus scan: the core circle with its one cycle", "[pointset][pipelines]") {
  REQUIRE(is_point_set_file(load_pipeline(pipeline("pointcloud_vmas.yaml"), shipped_registry()).input));
  const MedialComplex medial = run_shipped("pointcloud_vmas");
  CHECK(medial.num_vertices() == 30);
  const services::ComplexTopology top = services::complex_topology(medial);
  CHECK(top.b0 == 1);
  CHECK(top.b1 == 1);
  CHECK(median_core_distance(medial) < 0.05);
}

TEST_CASE("pointcloud_dey_zhao on a raw torus scan: facets around the core circle", "[pointset][pipelines]") {
  const MedialComplex medial = run_shipped("pointcloud_dey_zhao");
  CHECK(medial.faces.size() > 100);
  CHECK(median_core_distance(medial) < 0.05);
  CHECK(services::complex_topology(medial).b1 >= 1);  // around the hole of the torus
}

TEST_CASE("a mesh through a point-cloud pipeline is refused naming what the stage works on",
          "[pointset][pipelines]") {
  Overrides overrides;
  overrides.input = test::data_dir() / "cube.off";
  const auto out = test::scratch_dir("pointcloud_on_mesh") / "run";
  const RunResult result = test::run_quietly(pipeline("pointcloud_vmas.yaml"), shipped_registry(), out, overrides);
  CHECK_FALSE(result.ok);
  CHECK_THAT(result.error, Catch::Contains("the shape has no points"));
}

TEST_CASE("a point cloud through a mesh pipeline: the error says the input is a point cloud",
          "[pointset][pipelines]") {
  Overrides overrides;
  overrides.input = test::source_dir() / "tests" / "pointset" / "data" / "torus_scan.xyz";
  const auto out = test::scratch_dir("mesh_pipeline_on_cloud") / "run";
  const RunResult result = test::run_quietly(pipeline("vmas.yaml"), shipped_registry(), out, overrides);
  CHECK_FALSE(result.ok);
  CHECK_THAT(result.error, Catch::Contains("torus_scan.xyz is a point cloud of"));
  CHECK_THAT(result.error, Catch::Contains("docs/pointclouds.md"));
}

TEST_CASE("every shipped mesh pipeline refuses a point cloud naming the stage that makes a mesh",
          "[pointset][pipelines]") {
  Overrides overrides;
  overrides.input = test::source_dir() / "tests" / "pointset" / "data" / "torus_scan.xyz";
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() / "pipelines")) {
    const std::filesystem::path file = entry.path();
    const std::string name = file.filename().string();
    if (file.extension() != ".yaml" || name.rfind("pointcloud_", 0) == 0 || is_sweep(file)) continue;
    INFO(name);
    const RunResult result =
        test::run_quietly(file, shipped_registry(), test::scratch_dir("cloud_through_" + file.stem().string()) / "run",
                          overrides);
    CHECK_FALSE(result.ok);
    CHECK_THAT(result.error, Catch::Contains("reconstruct_mesh"));
  }
}
