// kill -9, SIGTERM and SIGINT at seeded random moments of a run and of a sweep (issue 13): the
// run folder is the previous run untouched or one complete run, never torn or mixed; the next run
// leaves no debris; exit codes are 130/143 (or death by the signal before the handlers are set,
// or 0 when the run won the race); a sweep resumed after the fault gives the uninterrupted
// sweep's results.csv.
#include "fault_helpers.hpp"

#include <sstream>

using namespace medax::test;
namespace fs = std::filesystem;

namespace {

const std::string kPlugins = plugin_dir("sweep").string() + ":" + good_plugins();

/// A run of ~0.2 s: read, centroid, sleep, count, one medial output. `seed` marks which run wrote a folder.
std::string sleepy_pipeline(int seed, double seconds) {
  return "input: " + data_file("cube.off") + "\nseed: " + std::to_string(seed) +
         "\nstages:\n  - plugin: test_centroid\n  - plugin: test_sleep\n    params: {seconds: " +
         std::to_string(seconds) + "}\n  - plugin: test_count\noutputs:\n  medial: [ma]\n";
}

/// The exit a signal may give: handled (128 + n), death by it before the handlers were installed,
/// or success when the run ended first. SIGKILL: death, or success.
void check_signal_ending(const Ending& e, int sig) {
  INFO("signal " << sig << ", wait status " << e.status);
  if (e.signalled()) CHECK(WTERMSIG(e.status) == sig);
  else CHECK((e.code() == 0 || (sig != SIGKILL && e.code() == 128 + sig)));
}

/// After a fault, `out` is the previous run unchanged, or one complete run of `seed` (never a mix).
void check_after_fault(const fs::path& out, const std::map<std::string, std::string>& before, int seed) {
  if (fs::is_symlink(out)) {  // a killed run into a fresh folder: the link to its staging folder
    CHECK(before.empty());
    return;
  }
  const auto now = snapshot(out);
  if (now == before) return;
  const nlohmann::json run = check_complete_run(out);
  CHECK(now.count("previous_only.txt") == 0);  // nothing of the previous run
  CHECK_THAT(now.at("config.resolved.yaml"), Catch::Contains("seed: " + std::to_string(seed)));
}

/// The rows of results.csv without the timing columns (time.*, peak_memory_mib).
std::vector<std::string> untimed_rows(const fs::path& csv) {
  std::istringstream in(read_text(csv));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  REQUIRE_FALSE(lines.empty());
  const auto cells = [](const std::string& line) {
    std::vector<std::string> out;
    std::istringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
    return out;
  };
  const std::vector<std::string> header = cells(lines[0]);
  std::vector<std::string> rows;
  for (const std::string& line : lines) {
    const std::vector<std::string> row = cells(line);
    std::string kept;
    for (std::size_t i = 0; i < row.size() && i < header.size(); ++i)
      if (header[i].rfind("time.", 0) != 0 && header[i] != "peak_memory_mib") kept += row[i] + ",";
    rows.push_back(kept);
  }
  return rows;
}

}  // namespace

TEST_CASE("a run killed at random moments leaves the previous run or a complete one, and no debris", "[faults][kill]") {
  const auto dir = scratch_dir("faults_kill_run");
  const fs::path out = dir / "runs" / "out";
  int seed = 100;
  const auto delays = seeded_delays_ms(13, 5, 260);
  for (const int sig : {SIGKILL, SIGTERM, SIGINT}) {
    int stopped = 0;  // runs the signal stopped (not all may: the run can end first)
    for (std::size_t i = 0; i < delays.size(); ++i) {
      const bool fresh = i % 2 == 0;  // into a new folder, or over a previous run
      if (fresh) fs::remove_all(out);
      else if (!fs::exists(out / "run.json")) {
        const auto file = write_text(dir / "previous.yaml", sleepy_pipeline(seed, 0));
        REQUIRE(run_medax("run '" + file.string() + "' --out '" + out.string() + "' --quiet", kPlugins, dir).code == 0);
        write_text(out / "previous_only.txt", "added to the previous run\n");
      }
      const auto before = snapshot(out);
      const auto file = write_text(dir / "p.yaml", sleepy_pipeline(++seed, 0.15));
      INFO("signal " << sig << " after " << delays[i] << " ms, " << (fresh ? "fresh folder" : "over a run"));
      const Ending e = run_and_kill({"run", file.string(), "--out", out.string(), "--quiet"}, kPlugins, dir, sig,
                                    delays[i]);
      check_signal_ending(e, sig);
      stopped += e.code() != 0;
      check_after_fault(out, before, seed);
      // The next run cleans up what the fault left and publishes a complete run.
      const auto next = write_text(dir / "next.yaml", sleepy_pipeline(++seed, 0));
      REQUIRE(run_medax("run '" + next.string() + "' --out '" + out.string() + "' --quiet", kPlugins, dir).code == 0);
      CHECK(check_complete_run(out)["status"] == "ok");
      CHECK(debris(dir / "runs").empty());
    }
    CHECK(stopped > 0);  // the seeded delays include moments inside the run (61 ms of ~200)
  }
}

TEST_CASE("a run killed as it publishes leaves the previous run or the complete new one", "[faults][kill]") {
  // The last stage's "done" line: what follows is the outputs, run.json and the exchange of folders.
  const auto dir = scratch_dir("faults_kill_publish");
  const fs::path out = dir / "runs" / "out";
  int seed = 200;
  for (const int sig : {SIGKILL, SIGTERM, SIGINT}) {
    for (int round = 0; round < 3; ++round) {
      const auto previous = write_text(dir / "previous.yaml", sleepy_pipeline(++seed, 0));
      REQUIRE(run_medax("run '" + previous.string() + "' --out '" + out.string() + "' --quiet", kPlugins, dir).code == 0);
      write_text(out / "previous_only.txt", "added to the previous run\n");
      const auto before = snapshot(out);
      const auto file = write_text(dir / "p.yaml", sleepy_pipeline(++seed, 0));
      INFO("signal " << sig << ", round " << round);
      const auto staging_log = [&](pid_t pid) {
        return out.parent_path() / ("out.partial-" + std::to_string(pid)) / "log.txt";
      };
      const Ending e = run_and_kill_at({"run", file.string(), "--out", out.string(), "--quiet"}, kPlugins, dir, sig,
                                       staging_log, "(test_count) done");
      check_signal_ending(e, sig);
      check_after_fault(out, before, seed);
      const auto next = write_text(dir / "next.yaml", sleepy_pipeline(++seed, 0));
      REQUIRE(run_medax("run '" + next.string() + "' --out '" + out.string() + "' --quiet", kPlugins, dir).code == 0);
      check_complete_run(out);
      CHECK(debris(dir / "runs").empty());
    }
  }
}

TEST_CASE("a sweep killed at random moments and resumed gives the uninterrupted sweep's results", "[faults][kill][sweep]") {
  const auto dir = scratch_dir("faults_kill_sweep");
  const std::string sweep = sleepy_pipeline(7, 0) + "sweep:\n  test_sleep.seconds: [0.05, 0.1, 0.15, 0.2, 0.25]\n";
  const auto file = write_text(dir / "s.yaml", sweep);
  const auto run_sweep = [&](const fs::path& out) {
    return "run '" + file.string() + "' --out '" + out.string() + "' -j 2 --quiet";
  };
  REQUIRE(run_medax(run_sweep(dir / "reference"), kPlugins, dir).code == 0);
  const auto reference = untimed_rows(dir / "reference" / "results.csv");
  REQUIRE(reference.size() == 6);

  const auto delays = seeded_delays_ms(31, 3, 500);
  for (const int sig : {SIGKILL, SIGTERM, SIGINT}) {
    int stopped = 0;
    for (const int delay : delays) {
      INFO("signal " << sig << " after " << delay << " ms");
      const fs::path out = dir / "swept";
      fs::remove_all(out);
      const Ending e =
          run_and_kill({"run", file.string(), "--out", out.string(), "-j", "2", "--quiet"}, kPlugins, dir, sig, delay);
      check_signal_ending(e, sig);
      stopped += e.code() != 0;
      // Every job folder is unpublished (absent or a link) or a complete run; its status.json parses.
      if (fs::exists(out / "jobs"))
        for (const auto& job : fs::directory_iterator(out / "jobs")) {
          if (job.path().filename().string().find(".partial-") != std::string::npos || fs::is_symlink(job.path()))
            continue;
          if (fs::exists(job.path() / "run.json")) check_complete_run(job.path(), {"output.txt", "status.json"});
          if (fs::exists(job.path() / "status.json"))
            CHECK_NOTHROW(nlohmann::json::parse(read_text(job.path() / "status.json")));
        }
      const auto resumed = run_medax(run_sweep(out), kPlugins, dir);
      INFO(resumed.err);
      REQUIRE(resumed.code == 0);
      CHECK(untimed_rows(out / "results.csv") == reference);
      CHECK(debris(dir).empty());
    }
    CHECK(stopped > 0);  // the seeded delays include moments inside the sweep (143 ms of ~600)
  }
}
