// Running a pipeline: the run folder's contents, output frames, and a failing stage that stops
// the run while keeping what the stages before it produced.
#include "run_helpers.hpp"

#include <medax/io.hpp>

#include <cmath>

using namespace medax;
using medax::test::data_file;
using medax::test::read_json;
using medax::test::read_text;
using medax::test::run_yaml;
using medax::test::scratch_dir;

namespace fs = std::filesystem;

namespace {
const std::string kInput = "input: " + data_file("cube.off") + "\n";  // the cube [-1, 1]^3
const double kCubeRadius = std::sqrt(3.0);                              // centroid to corner

std::string stage_done(const std::string& id) { return "stage '" + id + "' (" + id + ") done in"; }
}  // namespace

TEST_CASE("a run writes the resolved config and log and metrics and timings and the named outputs", "[runner]") {
  const auto run = run_yaml(scratch_dir("runner_folder"),
                            kInput + "stages:\n"
                                     "  - plugin: test_scale\n    params: {factor: 2}\n"
                                     "  - plugin: test_centroid\n"
                                     "  - plugin: test_radius_field\n"
                                     "  - plugin: test_count\n"
                                     "outputs: {medial: [ma, ply, obj], surface: [off]}\n");
  INFO(run.result.error);
  REQUIRE(run.result.ok);
  CHECK(run.result.failed_stage.empty());
  CHECK(run.result.out_dir == run.dir);

  CHECK(read_text(run.dir / "config.resolved.yaml") == resolved_yaml(run.config));

  const std::string log = read_text(run.dir / "log.txt");
  for (const char* id : {"test_scale", "test_centroid", "test_radius_field", "test_count"})
    CHECK_THAT(log, Catch::Contains(stage_done(id)));
  CHECK_THAT(log, Catch::Contains("peak memory"));

  const auto metrics = read_json(run.dir / "metrics.json");
  CHECK(metrics == nlohmann::json::parse(R"({"test_count": {"vertices": 1, "edges": 0, "faces": 0}})"));

  const auto timings = read_json(run.dir / "timings.json");
  REQUIRE(timings["stages"].size() == 4);
  CHECK(timings["stages"][0]["id"] == "test_scale");
  CHECK(timings["stages"][3]["plugin"] == "test_count");
  for (const auto& stage : timings["stages"]) {
    CHECK(stage["ok"] == true);
    CHECK(stage["seconds"].get<double>() >= 0.0);
  }
  CHECK(timings["total_seconds"].get<double>() >= 0.0);

  // Outputs are in the input's frame: the scaling is undone.
  const MedialComplex medial = read_ma(run.dir / "medial.ma");
  REQUIRE(medial.num_vertices() == 1);
  CHECK(medial.centres[0].norm() < 1e-12);
  CHECK(medial.radii[0] == Approx(kCubeRadius).epsilon(1e-12));
  CHECK_THAT(read_text(run.dir / "medial.ply"), Catch::Contains("property double radius_times"));
  CHECK_THAT(read_text(run.dir / "medial.obj"), Catch::Contains("\nv 0 0 0\n"));
  const SurfaceMesh surface = read_mesh(run.dir / "surface.off");
  const SurfaceMesh input = read_mesh(data_file("cube.off"));
  REQUIRE(surface.vertices.size() == input.vertices.size());
  for (std::size_t i = 0; i < input.vertices.size(); ++i)
    CHECK((surface.vertices[i] - input.vertices[i]).norm() < 1e-12);
  CHECK_FALSE(fs::exists(run.dir / "surface.ply"));  // only what the pipeline names
}

TEST_CASE("outputs in the working frame keep the conditioning stage's scaling", "[runner]") {
  const auto run = run_yaml(scratch_dir("runner_working_frame"),
                            kInput + "stages:\n  - plugin: test_scale\n    params: {factor: 2}\n"
                                     "  - plugin: test_centroid\noutputs: {medial: ma, frame: working}\n");
  REQUIRE(run.result.ok);
  CHECK(read_ma(run.dir / "medial.ma").radii[0] == Approx(2 * kCubeRadius).epsilon(1e-12));
  CHECK_FALSE(fs::exists(run.dir / "medial.ply"));
}

TEST_CASE("stages log through their context and write extra outputs into the run folder", "[runner]") {
  const auto run = run_yaml(scratch_dir("runner_context"),
                            kInput + "stages:\n  - plugin: test_centroid\n"
                                     "  - {plugin: test_count, id: counter, params: {log: true, element: vertices}}\n");
  REQUIRE(run.result.ok);
  CHECK_THAT(read_text(run.dir / "log.txt"), Catch::Contains("[counter] counted vertices"));
  CHECK_THAT(read_text(run.dir / "log.txt"), Catch::Contains("[counter] wrote counts.txt"));
  CHECK(read_text(run.dir / "counts.txt") == "vertices 1\n");
}

TEST_CASE("a pipeline can start from a medial axis read from a .ma file", "[runner]") {
  const auto root = scratch_dir("runner_medial_input");
  MedialComplex given;
  given.add_vertex(Vec3(0.5, 0, 0), 0.25);
  given.add_vertex(Vec3(-0.5, 0, 0), 0.25);
  given.add_edge(0, 1);
  write_ma(root / "given.ma", given);
  const auto run = run_yaml(root, kInput + "medial_input: given.ma\nstages:\n  - plugin: test_count\n"
                                           "outputs: {medial: ma}\n");
  REQUIRE(run.result.ok);
  CHECK(read_json(run.dir / "metrics.json")["test_count"]["edges"] == 1);
  CHECK(read_text(run.dir / "medial.ma") == read_text(root / "given.ma"));
}

TEST_CASE("a failing stage stops the run and earlier outputs remain", "[runner]") {
  const auto run = run_yaml(scratch_dir("runner_failure"),
                            kInput + "stages:\n"
                                     "  - plugin: test_centroid\n"
                                     "  - plugin: test_count\n"
                                     "  - {plugin: test_fail, id: boom, params: {message: planned failure}}\n"
                                     "  - plugin: test_random\n");
  CHECK_FALSE(run.result.ok);
  CHECK(run.result.failed_stage == "boom");
  CHECK(run.result.error == "boom: planned failure");  // under the stage id

  // The complex as the extraction left it: the failing stage's partial changes are discarded.
  const MedialComplex medial = read_ma(run.dir / "medial.ma");
  REQUIRE(medial.num_vertices() == 1);
  CHECK(medial.radii[0] == Approx(kCubeRadius).epsilon(1e-12));
  CHECK(fs::exists(run.dir / "medial.ply"));
  CHECK(fs::exists(run.dir / "config.resolved.yaml"));

  const auto metrics = read_json(run.dir / "metrics.json");
  CHECK(metrics.contains("test_count"));
  CHECK_FALSE(metrics.contains("test_random"));  // never ran

  const auto timings = read_json(run.dir / "timings.json");
  REQUIRE(timings["stages"].size() == 3);
  CHECK(timings["stages"][1]["ok"] == true);
  CHECK(timings["stages"][2]["id"] == "boom");
  CHECK(timings["stages"][2]["ok"] == false);

  const std::string log = read_text(run.dir / "log.txt");
  CHECK_THAT(log, Catch::Contains("stage 'boom' (test_fail) failed"));
  CHECK_THAT(log, Catch::Contains("planned failure"));
  CHECK_THAT(log, !Catch::Contains("test_random"));

  // No temporary files are left behind.
  for (const auto& entry : fs::directory_iterator(run.dir))
    CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);
}

TEST_CASE("an unreadable input stops the run before any stage", "[runner]") {
  const auto root = scratch_dir("runner_bad_input");
  medax::test::write_text(root / "broken.off", "OFF\n3 1 0\n0 0 0\n1 0\n");
  const auto run = run_yaml(root, "input: broken.off\nstages:\n  - plugin: test_centroid\n");
  CHECK_FALSE(run.result.ok);
  CHECK(run.result.failed_stage == "input");
  CHECK_THAT(run.result.error, Catch::Contains("broken.off"));
  CHECK(fs::exists(run.dir / "config.resolved.yaml"));
  CHECK_FALSE(fs::exists(run.dir / "medial.ma"));
}
