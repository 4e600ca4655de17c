// The `medax` command line end to end: plugins, describe, validate, run, and exit codes
// (0 success, 1 a stage failed, 2 bad usage or invalid pipeline).
#include "cli_helpers.hpp"

#include <cstdio>
#include <sys/wait.h>

using medax::test::cube_pipeline;
using medax::test::data_file;
using medax::test::run_medax;
using medax::test::plugin_dir;
using medax::test::read_text;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace fs = std::filesystem;

namespace {

const std::string& kGood = medax::test::good_plugins();

}  // namespace

TEST_CASE("medax plugins lists the stages ordered by role with package and version", "[cli]") {
  const auto r = run_medax("plugins", kGood, scratch_dir("cli_plugins"));
  INFO(r.out << r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.rfind("ROLE", 0) == 0);
  const auto scale = r.out.find("conditioning");
  const auto centroid = r.out.find("test_centroid");
  const auto count = r.out.find("test_count");
  REQUIRE(scale != std::string::npos);
  REQUIRE(centroid != std::string::npos);
  REQUIRE(count != std::string::npos);
  CHECK(scale < centroid);
  CHECK(centroid < count);
  CHECK_THAT(r.out, Catch::Contains("kernel_test"));
  CHECK_THAT(r.out, Catch::Contains("1.2.3"));
  CHECK_THAT(r.out, Catch::Contains("Count medial elements (kernel test stage)"));
}

TEST_CASE("medax plugins reports a broken plugin on one line and exits 2", "[cli]") {
  const auto r = run_medax("plugins", kGood + ":" + plugin_dir("bad_abi").string(), scratch_dir("cli_plugins_broken"));
  CHECK(r.code == 2);
  CHECK_THAT(r.out, Catch::Contains("test_scale"));  // the good ones are still listed
  CHECK_THAT(r.err, Catch::StartsWith("error: plugin " + plugin_dir("bad_abi").string()));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

TEST_CASE("medax describe prints every parameter with type default and range", "[cli]") {
  const auto dir = scratch_dir("cli_describe");
  const auto r = run_medax("describe test_count", kGood, dir);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("test_count (evaluation stage, package kernel_test 1.2.3)"));
  CHECK_THAT(r.out, Catch::Contains("PARAMETER"));
  CHECK_THAT(r.out, Catch::Matches("(.|\n)*element +choice +all +one of all\\|vertices\\|edges\\|faces +what to count(.|\n)*"));
  CHECK_THAT(r.out, Catch::Matches("(.|\n)*log +bool +false +log the counts and write them to counts.txt(.|\n)*"));

  const auto scale = run_medax("describe test_scale", kGood, dir);
  CHECK_THAT(scale.out, Catch::Matches("(.|\n)*factor +real +1 +\\[0.001, 1000\\] +scale factor(.|\n)*"));

  const auto unknown = run_medax("describe test_scal", kGood, dir);
  CHECK(unknown.code == 2);
  CHECK_THAT(unknown.err, Catch::Contains("no stage named 'test_scal'"));
  CHECK_THAT(unknown.err, Catch::Contains("test_scale"));
}

TEST_CASE("medax validate accepts a good pipeline and rejects a bad one with file:line:col", "[cli]") {
  const auto dir = scratch_dir("cli_validate");
  const auto good = write_text(dir / "good.yaml", cube_pipeline("  - plugin: test_centroid\n  - plugin: test_count\n"));
  const auto ok = run_medax("validate '" + good.string() + "'", kGood, dir);
  CHECK(ok.code == 0);
  CHECK_THAT(ok.out, Catch::Contains("valid (2 stages: test_centroid -> test_count)"));

  const auto bad = write_text(dir / "bad.yaml", cube_pipeline("  - plugin: test_centriod\n"));
  const auto r = run_medax("validate '" + bad.string() + "'", kGood, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(bad.string() + ":4:13: error: unknown plugin 'test_centriod'"));
  CHECK_THAT(r.err, Catch::Contains("did you mean 'test_centroid'"));

  const auto set = run_medax("validate '" + good.string() + "' --set test_count.element=nodes", kGood, dir);
  CHECK(set.code == 2);
  CHECK_THAT(set.err, Catch::Contains("--set test_count.element=nodes: error:"));
}

TEST_CASE("medax run writes the run folder and exits 0", "[cli]") {
  const auto dir = scratch_dir("cli_run");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_scale\n  - plugin: test_centroid\n"
                                                        "  - plugin: test_count\n"));
  const auto r = run_medax("run '" + file.string() + "' --out '" + (dir / "run").string() +
                           "' --set test_scale.factor=4 --quiet",
                       kGood, dir);
  INFO(r.out << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("results: " + (dir / "run").string()));
  for (const char* name : {"config.resolved.yaml", "log.txt", "metrics.json", "timings.json", "medial.ma", "medial.ply"})
    CHECK(fs::exists(dir / "run" / name));
  CHECK_THAT(read_text(dir / "run" / "config.resolved.yaml"), Catch::Contains("factor: 4.0"));
  CHECK_THAT(read_text(dir / "run" / "metrics.json"), Catch::Contains("\"vertices\": 1"));
}

TEST_CASE("medax run with a failing stage exits 1 naming the stage", "[cli]") {
  const auto dir = scratch_dir("cli_run_fail");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n  - plugin: test_fail\n"));
  const auto r = run_medax("run '" + file.string() + "' --out '" + (dir / "run").string() + "' --quiet", kGood, dir);
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains("error: test_fail: test_fail failed on purpose"));
  CHECK(fs::exists(dir / "run" / "medial.ma"));
}

TEST_CASE("medax run of an invalid pipeline exits 2 and runs nothing", "[cli]") {
  const auto dir = scratch_dir("cli_run_invalid");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_count\n"));
  const auto r = run_medax("run '" + file.string() + "' --out '" + (dir / "run").string() + "'", kGood, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(file.string() + ":4:5: error:"));
  CHECK_FALSE(fs::exists(dir / "run"));
}

TEST_CASE("medax run --backend slurm on a single pipeline exits 2 and runs nothing", "[cli]") {
  const auto dir = scratch_dir("cli_run_backend_single");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n"));
  const auto r = run_medax("run '" + file.string() + "' --backend slurm --out '" + (dir / "run").string() + "'", kGood,
                           dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("--backend slurm runs the jobs of an experiment"));
  CHECK_FALSE(fs::exists(dir / "run"));
}
