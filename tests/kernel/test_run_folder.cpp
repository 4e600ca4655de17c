// The run folder contract: a run is written into a staging folder beside --out and renamed into
// place when it ends, with run.json written last; a previous run folder is replaced whole, a
// folder that is not a run is refused, and what killed runs left behind is removed.
#include "run_helpers.hpp"

#include <medax/io.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <regex>

using namespace medax;
using medax::test::data_file;
using medax::test::read_json;
using medax::test::read_text;
using medax::test::run_yaml;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace fs = std::filesystem;

namespace {
const std::string kInput = "input: " + data_file("cube.off") + "\n";

std::vector<std::string> contents(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Writes `text` to `path`, creating its folder.
fs::path put(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  return write_text(path, text);
}

/// No temporary file in the run folder and no staging folder beside it.
void check_no_leftovers(const fs::path& root, const fs::path& run) {
  for (const std::string& name : contents(run)) {
    INFO(name);
    CHECK(name.find(".tmp") == std::string::npos);
  }
  for (const std::string& name : contents(root)) {
    INFO(name);
    CHECK(name.find(".partial-") == std::string::npos);
    CHECK(name.find(".replaced-") == std::string::npos);
  }
}

/// The pid of a process that has ended (a child, reaped): nothing runs under it.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) ::_exit(0);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  return pid;
}

const std::string kFull = kInput + "stages:\n"
                                   "  - plugin: test_centroid\n"
                                   "  - {plugin: test_count, params: {log: true}}\n"
                                   "outputs: {medial: [ma, ply], surface: [off]}\n";
}  // namespace

TEST_CASE("run.json is written last and says how the run ended", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_marker");
  const auto run = run_yaml(root, kFull);
  INFO(run.result.error);
  REQUIRE(run.result.ok);
  CHECK(run.result.out_dir == run.dir);
  CHECK_FALSE(fs::is_symlink(run.dir));
  const auto marker = read_json(run.dir / "run.json");
  CHECK(marker["status"] == "ok");
  CHECK(marker["failed_stage"].is_null());
  CHECK(marker["error"].is_null());
  CHECK(marker["signal"].is_null());
  CHECK(marker["medax_version"] == std::string(kVersion));
  CHECK(marker["pipeline"] == run.config.name);
  const std::regex utc(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)");
  CHECK(std::regex_match(marker["started"].get<std::string>(), utc));
  CHECK(std::regex_match(marker["ended"].get<std::string>(), utc));
  CHECK(marker["started"].get<std::string>() <= marker["ended"].get<std::string>());
  // Every file of the run is there, and the staging folder is gone.
  CHECK(contents(run.dir) == std::vector<std::string>{"config.resolved.yaml", "counts.txt", "log.txt", "medial.ma",
                                                      "medial.ply", "metrics.json", "run.json", "surface.off",
                                                      "timings.json"});
  check_no_leftovers(root, run.dir);
}

TEST_CASE("a re-run with fewer outputs leaves no file of the first run", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_rerun");
  const auto first = run_yaml(root, kFull);
  REQUIRE(first.result.ok);
  REQUIRE(fs::exists(first.dir / "counts.txt"));
  write_text(first.dir / "notes.txt", "a file the user put into the run folder\n");
  const auto second = run_yaml(root, kInput + "stages:\n  - plugin: test_centroid\noutputs: {medial: [ma]}\n");
  INFO(second.result.error);
  REQUIRE(second.result.ok);
  CHECK(contents(second.dir) == std::vector<std::string>{"config.resolved.yaml", "log.txt", "medial.ma",
                                                         "metrics.json", "run.json", "timings.json"});
  CHECK(read_text(second.dir / "config.resolved.yaml") == resolved_yaml(second.config));
  // One run's log: nothing of the first run's.
  CHECK_THAT(read_text(second.dir / "log.txt"), !Catch::Contains("test_count"));
  check_no_leftovers(root, second.dir);
}

TEST_CASE("a failed run replaces the previous run whole and is marked failed", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_failed");
  REQUIRE(run_yaml(root, kFull).result.ok);
  const auto run = run_yaml(root, kInput + "stages:\n  - plugin: test_centroid\n"
                                           "  - {plugin: test_fail, id: boom, params: {message: planned failure}}\n"
                                           "outputs: {medial: [ma]}\n");
  CHECK_FALSE(run.result.ok);
  CHECK(run.result.failed_stage == "boom");
  CHECK(run.result.out_dir == run.dir);
  const auto marker = read_json(run.dir / "run.json");
  CHECK(marker["status"] == "failed");
  CHECK(marker["failed_stage"] == "boom");
  CHECK(marker["error"] == "boom: planned failure");
  CHECK(marker["signal"].is_null());
  // Nothing of the first run: its PLY axis, surface and counts are gone.
  for (const char* old : {"medial.ply", "surface.off", "counts.txt"}) {
    INFO(old);
    CHECK_FALSE(fs::exists(run.dir / old));
  }
  CHECK(read_json(run.dir / "metrics.json") == nlohmann::json::object());
  CHECK_THAT(read_text(run.dir / "log.txt"), Catch::Contains("planned failure"));
  check_no_leftovers(root, run.dir);
}

TEST_CASE("a run whose input cannot be read is published, marked failed at 'input'", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_bad_input");
  REQUIRE(run_yaml(root, kFull).result.ok);
  write_text(root / "broken.off", "OFF\n3 1 0\n0 0 0\n1 0\n");
  const auto run = run_yaml(root, "input: broken.off\nstages:\n  - plugin: test_centroid\n");
  CHECK(run.result.failed_stage == "input");
  CHECK(read_json(run.dir / "run.json")["status"] == "failed");
  CHECK(read_json(run.dir / "run.json")["failed_stage"] == "input");
  CHECK_FALSE(fs::exists(run.dir / "medial.ma"));
  CHECK_FALSE(fs::exists(run.dir / "counts.txt"));
  check_no_leftovers(root, run.dir);
}

TEST_CASE("a folder with files that is not a run folder is refused and left untouched", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_foreign");
  const fs::path mine = root / "run";
  put(mine / "thesis.tex", "my thesis\n");
  fs::create_directories(mine / "figures");
  const auto run = run_yaml(root, kFull);
  CHECK_FALSE(run.result.ok);
  CHECK_FALSE(run.result.wrote_log);
  CHECK(run.result.failed_stage == "run folder");
  CHECK_THAT(run.result.error, Catch::Contains("cannot use " + mine.string() + " as the run folder"));
  CHECK_THAT(run.result.error, Catch::Contains("not a medax run folder"));
  CHECK_THAT(run.result.error, Catch::Contains("--out"));
  CHECK(contents(mine) == std::vector<std::string>{"figures", "thesis.tex"});
  CHECK(read_text(mine / "thesis.tex") == "my thesis\n");
  CHECK(contents(root) == std::vector<std::string>{"pipeline.yaml", "run"});  // no staging folder made
}

TEST_CASE("an empty existing folder becomes the run folder", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_empty");
  fs::create_directories(root / "run");
  const auto run = run_yaml(root, kFull);
  INFO(run.result.error);
  REQUIRE(run.result.ok);
  CHECK(read_json(run.dir / "run.json")["status"] == "ok");
  check_no_leftovers(root, run.dir);
}

TEST_CASE("the staging folder of a killed run is removed and named by the next run", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_killed");
  REQUIRE(run_yaml(root, kFull).result.ok);
  // What kill -9 leaves: a staging folder with some files and no run.json, and the previous
  // run untouched. Also the aside folder of a kill between the two renames of a fallback publish.
  const fs::path stale = root / ("run.partial-" + std::to_string(dead_pid()));
  put(stale / "log.txt", "half a log\n");
  put(stale / "medial.ma", "v 0 0 0 1\n");
  const fs::path aside = root / ("run.replaced-" + std::to_string(dead_pid()));
  put(aside / "run.json", "{}\n");
  // A folder that only looks alike, and the staging folder of a run that is still going (this
  // process stands in for it), are left alone.
  const fs::path other = root / "run.partial-abc";
  put(other / "keep.txt", "keep\n");
  const fs::path live = root / ("run.partial-" + std::to_string(::getppid()));
  put(live / "log.txt", "a run still going\n");

  const auto run = run_yaml(root, kInput + "stages:\n  - plugin: test_centroid\noutputs: {medial: [ma]}\n");
  INFO(run.result.error);
  REQUIRE(run.result.ok);
  CHECK_FALSE(fs::exists(stale));
  CHECK_FALSE(fs::exists(aside));
  CHECK(fs::exists(other / "keep.txt"));
  CHECK(fs::exists(live / "log.txt"));
  const std::string log = read_text(run.dir / "log.txt");
  CHECK_THAT(log, Catch::Contains("removed " + stale.string() + ": the unfinished run folder of a run that was killed"));
  CHECK_THAT(log, Catch::Contains("removed " + aside.string()));
  CHECK_FALSE(fs::exists(run.dir / "counts.txt"));  // the previous run was replaced
}

TEST_CASE("a link left at the target by a killed run is removed with its staging folder", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_killed_link");
  const std::string staging = "run.partial-" + std::to_string(dead_pid());
  put(root / staging / "log.txt", "half a log\n");
  fs::create_directory_symlink(staging, root / "run");
  const auto run = run_yaml(root, kFull);
  INFO(run.result.error);
  REQUIRE(run.result.ok);
  CHECK_FALSE(fs::is_symlink(run.dir));
  CHECK(read_json(run.dir / "run.json")["status"] == "ok");
  CHECK_FALSE(fs::exists(root / staging));
  check_no_leftovers(root, run.dir);
}

TEST_CASE("a run into a folder that a live run is writing is refused", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_busy");
  // A run going on in another process (the parent of this test stands in for it).
  const std::string staging = "run.partial-" + std::to_string(::getppid());
  put(root / staging / "log.txt", "a run still going\n");
  fs::create_directory_symlink(staging, root / "run");
  const auto run = run_yaml(root, kFull);
  CHECK_FALSE(run.result.ok);
  CHECK_THAT(run.result.error, Catch::Contains("another medax run (process " + std::to_string(::getppid())));
  CHECK(fs::is_symlink(root / "run"));
  CHECK(read_text(root / staging / "log.txt") == "a run still going\n");
}

TEST_CASE("a relative run folder is staged and published beside itself", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_relative");
  const auto config = load_pipeline(write_text(root / "pipeline.yaml", kFull), medax::test::good_registry());
  const fs::path before = fs::current_path();
  fs::current_path(root);
  RunOptions options;
  options.out_dir = "run";  // no parent in the path itself
  options.quiet = true;
  const RunResult first = run_pipeline(config, options);
  options.out_dir = "run/";  // a trailing separator names the same folder
  const RunResult second = run_pipeline(config, options);
  fs::current_path(before);
  INFO(first.error << " / " << second.error);
  CHECK(first.ok);
  CHECK(second.ok);
  CHECK(read_json(root / "run" / "run.json")["status"] == "ok");
  check_no_leftovers(root, root / "run");
}

// Last in this file: the interrupt flag stays raised for the rest of the process (ctest runs
// each test case in a process of its own).
TEST_CASE("an interrupted run is published, marked interrupted", "[runner][run_folder]") {
  const auto root = scratch_dir("run_folder_interrupted");
  REQUIRE(run_yaml(root, kFull).result.ok);  // also installs the runner's SIGINT/SIGTERM handler
  REQUIRE(::raise(SIGTERM) == 0);            // caught: the next run stops before its first stage
  const auto run = run_yaml(root, kInput + "stages:\n  - plugin: test_centroid\n  - plugin: test_count\n");
  CHECK_FALSE(run.result.ok);
  CHECK(run.result.signal == SIGTERM);
  CHECK(run.result.out_dir == run.dir);
  const auto marker = read_json(run.dir / "run.json");
  CHECK(marker["status"] == "interrupted");
  CHECK(marker["failed_stage"] == "test_centroid");
  CHECK(marker["signal"] == "SIGTERM");
  CHECK_THAT(marker["error"].get<std::string>(), Catch::Contains("interrupted by SIGTERM"));
  CHECK_FALSE(fs::exists(run.dir / "counts.txt"));  // nothing of the previous run
  CHECK_FALSE(fs::exists(run.dir / "medial.ma"));
  check_no_leftovers(root, run.dir);
}
