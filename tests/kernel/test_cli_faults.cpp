// `medax` under hostile input and faults (issue 13): unusable run folders and pipeline paths
// give a clear error and a non-zero exit (never `terminate`, exit 134), usage errors exit 2,
// SIGINT/SIGTERM stop a run cleanly with exit 130/143.
#include "cli_helpers.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <thread>

using medax::test::cube_pipeline;
using medax::test::data_file;
using medax::test::plugin_dir;
using medax::test::read_text;
using medax::test::run_medax;
using medax::test::scratch_dir;
using medax::test::spawn_medax;
using medax::test::write_text;

namespace fs = std::filesystem;

namespace {

const std::string& kGood = medax::test::good_plugins();

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

/// No abort, no uncaught exception: a clear one-line error instead.
void check_clean_error(const medax::test::Output& r) {
  CHECK_THAT(r.err, !Catch::Contains("terminate called"));
  CHECK_THAT(r.err, Catch::StartsWith("error: "));
}

/// Waits until `file` contains `text` (the run reached that point), at most `limit`.
bool wait_for_text(const fs::path& file, const std::string& text, std::chrono::seconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (fs::exists(file) && read_text(file).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

/// Runs a pipeline whose second stage sleeps, sends `sig` once the input was read (the signal
/// handler is installed by then), and returns the exit status.
int run_and_signal(int sig, const fs::path& dir) {
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n  - plugin: test_sleep\n"
                                                        "    params: {seconds: 2}\n  - plugin: test_count\n"));
  const pid_t pid = spawn_medax({"run", file.string(), "--out", (dir / "run").string(), "--quiet"},
                                plugin_dir("sweep").string() + ":" + kGood, dir);
  const bool started = wait_for_text(dir / "run" / "log.txt", "read ", std::chrono::seconds(60));
  if (started) ::kill(pid, sig);
  else ::kill(pid, SIGKILL);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(started);
  INFO(read_text(dir / "stderr.txt"));
  REQUIRE(WIFEXITED(status));  // a clean stop, not death by the signal
  return WEXITSTATUS(status);
}

}  // namespace

TEST_CASE("medax run with --out an existing regular file exits 1 naming it, the file untouched", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_out_file");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n"));
  const auto taken = write_text(dir / "taken", "keep me\n");
  const auto r = run_medax("run " + quoted(file) + " --out " + quoted(taken) + " --quiet", kGood, dir);
  CHECK(r.code == 1);
  check_clean_error(r);
  CHECK_THAT(r.err, Catch::Contains("cannot use " + taken.string() + " as the run folder: it exists and is not a folder"));
  CHECK_THAT(r.err, Catch::Contains("--out"));
  CHECK(read_text(taken) == "keep me\n");
}

TEST_CASE("medax run with --out under a regular file exits 1 naming the file", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_out_under_file");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n"));
  const auto taken = write_text(dir / "taken", "x\n");
  for (const fs::path out : {taken / "run", taken / "a" / "b"}) {
    const auto r = run_medax("run " + quoted(file) + " --out " + quoted(out) + " --quiet", kGood, dir);
    CHECK(r.code == 1);
    check_clean_error(r);
    CHECK_THAT(r.err, Catch::Contains("cannot create the run folder " + out.string() + ": " + taken.string() +
                                      " is a file, not a folder"));
  }
}

TEST_CASE("medax run into a folder it cannot write exits 1 with the reason", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_out_readonly");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n"));
  if (::geteuid() != 0) {
    // Permission bits stop an ordinary user.
    const auto locked = dir / "locked";
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    const auto r = run_medax("run " + quoted(file) + " --out " + quoted(locked / "run") + " --quiet", kGood, dir);
    fs::permissions(locked, fs::perms::owner_all);
    CHECK(r.code == 1);
    check_clean_error(r);
    CHECK_THAT(r.err, Catch::Contains("cannot create the run folder " + (locked / "run").string() +
                                      ": Permission denied"));
  } else {
    // Root writes through permission bits: in /sys nobody, root included, can make a folder.
    const auto r = run_medax("run " + quoted(file) + " --out /sys/medax-run --quiet", kGood, dir);
    CHECK(r.code == 1);
    check_clean_error(r);
    CHECK_THAT(r.err, Catch::Contains("cannot create the run folder /sys/medax-run: "));
    CHECK_FALSE(fs::exists("/sys/medax-run"));
  }
}

TEST_CASE("medax run, validate and bench of a folder as the pipeline exit 2 naming it", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_pipeline_dir");
  const auto folder = dir / "pipelines";
  fs::create_directories(folder);
  for (const std::string command : {"run", "validate", "bench"}) {
    const auto r = run_medax(command + " " + quoted(folder), kGood, dir);
    INFO(command);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, !Catch::Contains("terminate called"));
    CHECK_THAT(r.err, Catch::StartsWith(folder.string() + ": error: is a folder, not a pipeline file"));
  }
}

TEST_CASE("an error escaping a command is printed by main's last catch, exit 1", "[cli][faults]") {
  // A sweep into a regular file: thrown while creating the sweep's folders.
  const auto dir = scratch_dir("cli_faults_last_catch");
  const auto file = write_text(dir / "s.yaml", cube_pipeline("  - plugin: test_centroid\n  - plugin: test_sleep\n") +
                                                   "sweep:\n  test_sleep.seconds: [0, 0.01]\n");
  const auto taken = write_text(dir / "taken", "x\n");
  const auto r = run_medax("run " + quoted(file) + " --out " + quoted(taken) + " --quiet",
                           plugin_dir("sweep").string() + ":" + kGood, dir);
  CHECK(r.code == 1);
  check_clean_error(r);
}

TEST_CASE("medax usage errors exit 2, --help and --version exit 0", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_usage");
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n"));
  const std::vector<std::string> usage_errors{"run " + quoted(file) + " --bogus", "run",
                                              "run " + quoted(file) + " --jobs", "run " + quoted(file) + " --jobs 0",
                                              "", "frobnicate"};
  for (const std::string& args : usage_errors) {
    const auto r = run_medax(args, kGood, dir);
    INFO("medax " << args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::StartsWith("error: "));
    CHECK_THAT(r.err, Catch::Contains("--help"));
  }
  for (const std::string args : {"--help", "run --help", "--version"}) {
    const auto r = run_medax(args, kGood, dir);
    INFO("medax " << args);
    CHECK(r.code == 0);
    CHECK_FALSE(r.out.empty());
  }
}

TEST_CASE("SIGTERM during a run stops it cleanly with exit 143 and an interrupted log", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_sigterm");
  CHECK(run_and_signal(SIGTERM, dir) == 143);
  const std::string log = read_text(dir / "run" / "log.txt");
  CHECK_THAT(log, Catch::Contains("interrupted by SIGTERM"));
  CHECK_THAT(log, Catch::Contains("run interrupted at"));
  CHECK_THAT(log, !Catch::Contains("stage 'test_count' (test_count) done"));
  CHECK_THAT(read_text(dir / "stderr.txt"), Catch::Contains("error: interrupted by SIGTERM"));
  CHECK(fs::exists(dir / "run" / "timings.json"));
}

TEST_CASE("SIGINT during a run stops it cleanly with exit 130 and an interrupted log", "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_sigint");
  CHECK(run_and_signal(SIGINT, dir) == 130);
  const std::string log = read_text(dir / "run" / "log.txt");
  CHECK_THAT(log, Catch::Contains("interrupted by SIGINT"));
  CHECK_THAT(log, Catch::Contains("run interrupted at"));
  CHECK_THAT(log, !Catch::Contains("stage 'test_count' (test_count) done"));
}

TEST_CASE("a broken plugin on the path is one warning in validate, run and describe; exit codes unchanged",
          "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_broken_plugin");
  fs::create_directories(dir / "plugins");
  write_text(dir / "plugins" / "libmedax_broken.so", "not a shared library\n");
  const std::string path = kGood + ":" + (dir / "plugins").string();
  const std::string warning = "warning: plugin " + (dir / "plugins" / "libmedax_broken.so").string() + ": ";
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n  - plugin: test_count\n"));
  for (const std::string& args : {"validate " + quoted(file), "run --quiet " + quoted(file) + " --out " + quoted(dir / "run"),
                                  std::string("describe test_count")}) {
    INFO("medax " << args);
    const auto r = run_medax(args, path, dir);
    CHECK(r.code == 0);
    CHECK_THAT(r.err, Catch::StartsWith(warning));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // one line, nothing else
  }
}

TEST_CASE("a pipeline naming a stage of a broken plugin gets the load failure with its unknown-plugin error",
          "[cli][faults]") {
  const auto dir = scratch_dir("cli_faults_broken_plugin_needed");
  fs::create_directories(dir / "plugins");
  write_text(dir / "plugins" / "libmedax_broken.so", "not a shared library\n");
  const std::string path = kGood + ":" + (dir / "plugins").string();
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: broken_stage\n"));
  const auto r = run_medax("validate " + quoted(file), path, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("error: unknown plugin 'broken_stage'"));
  CHECK_THAT(r.err, Catch::Contains("note: 'broken_stage' may be in a plugin file that failed to load: plugin " +
                                    (dir / "plugins" / "libmedax_broken.so").string()));
  // A stage no broken file would provide gets no such note.
  const auto other = write_text(dir / "q.yaml", cube_pipeline("  - plugin: no_such_stage\n"));
  CHECK_THAT(run_medax("validate " + quoted(other), path, dir).err, !Catch::Contains("note: 'no_such_stage'"));
}
