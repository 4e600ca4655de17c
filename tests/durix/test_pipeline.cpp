// The durix package through the kernel: loaded from its .so, run as a pipeline, outputs in the
// run folder, deterministic bytes, and the refusal of a non-Delaunay input.
#include "pipeline_run.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>
#include <medax/testing/shapes.hpp>
#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

using namespace medax;

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

RunResult run(Registry& registry, const std::filesystem::path& dir, const std::string& stages,
              const std::string& out) {
  return test::run_yaml_text(dir, "name: durix_test\nseed: 0\ninput: box.off\nstages:\n" + stages +
                                      "outputs: {medial: [ma, ply]}\n",
                             registry, out);
}

}  // namespace

TEST_CASE("durix: the durix package runs as a pipeline and writes its outputs", "[durix][pipeline]") {
  Registry registry;
  REQUIRE(registry.load_file(MEDAX_DURIX_PLUGIN));
  for (const char* name : {"delaunay_surface", "durix", "durix_epsilon"}) REQUIRE(registry.find(name));
  const auto dir = test::scratch_dir("durix_pipeline");
  write_mesh(dir / "box.off", testing::make_box(1.0, 0.6, 0.3, 5));
  const std::string stages =
      "  - plugin: delaunay_surface\n"
      "  - plugin: durix\n"
      "    params: {oracle: {plugin: durix_epsilon, params: {epsilon: 0.02}}}\n";
  const RunResult a = run(registry, dir, stages, "a");
  INFO(a.error);
  REQUIRE(a.ok);
  for (const char* file : {"medial.ma", "medial.ply", "durix_surface.ply", "durix_segmentation.ply", "durix_sheets.json"})
    CHECK(std::filesystem::exists(dir / "a" / file));
  CHECK(slurp(dir / "a" / "durix_sheets.json").find("\"adjacency\"") != std::string::npos);
  const std::string segmentation = slurp(dir / "a" / "durix_segmentation.ply");
  CHECK(segmentation.find("property int sheet") != std::string::npos);
  CHECK(segmentation.find("property uchar red") != std::string::npos);
  const std::string medial_ply = slurp(dir / "a" / "medial.ply");
  CHECK(medial_ply.find("path_type") != std::string::npos);
  CHECK(medial_ply.find("sheet") != std::string::npos);
  // M_w read back: a closed mesh whose vertices are input vertices.
  const SurfaceMesh mw = read_mesh(dir / "a" / "durix_surface.ply");
  CHECK(!mw.faces.empty());
  // Same config and seed: the same bytes.
  const RunResult b = run(registry, dir, stages, "b");
  REQUIRE(b.ok);
  for (const char* file : {"medial.ma", "medial.ply", "durix_surface.ply", "durix_segmentation.ply", "durix_sheets.json"})
    CHECK(slurp(dir / "a" / file) == slurp(dir / "b" / file));
}

TEST_CASE("durix without delaunay_surface refuses a non-Delaunay mesh with the fix", "[durix][pipeline]") {
  Registry registry;
  REQUIRE(registry.load_file(MEDAX_DURIX_PLUGIN));
  const auto dir = test::scratch_dir("durix_refusal");
  write_mesh(dir / "box.off", testing::make_torus(1.0, 0.35, 48, 16));
  const RunResult r = run(registry, dir, "  - plugin: durix\n", "run");
  REQUIRE_FALSE(r.ok);
  CHECK(r.failed_stage == "durix");
  CHECK(r.error.find("delaunay_surface") != std::string::npos);
}
