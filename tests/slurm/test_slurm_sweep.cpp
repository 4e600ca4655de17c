// A sweep through a real single-node Slurm cluster (scripts/slurm-local.sh) gives the local
// backend's results: the same rows, the same status per job (a crash, a time-out with its cause),
// the same job folders. Also: --no-wait then --results-only, a task Slurm kills at its own time
// limit, and the errors when sbatch is missing or the cluster is down.
#include "cli_helpers.hpp"
#include "../../framework/src/slurm_commands.hpp"  // internal: the duration parsing tested below

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <thread>

using medax::test::data_file;
using medax::test::plugin_dir;
using medax::test::read_text;
using medax::test::run_medax;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace fs = std::filesystem;

namespace {

const std::string kPlugins = plugin_dir("good").string() + ":" + plugin_dir("sweep").string();
const fs::path kScript = fs::path(MEDAX_SOURCE_DIR) / "scripts" / "slurm-local.sh";

struct Shell {
  int code;
  std::string output;
};

Shell shell(const std::string& command) {
  Shell r{-1, ""};
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  REQUIRE(pipe);
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) r.output.append(buffer, n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// The cluster of one test: started in a fresh state folder under /tmp (short, for the munge
/// socket's path), stopped when the test ends. A cluster that does not start fails the test.
class LocalSlurm {
 public:
  LocalSlurm() {
    char name[] = "/tmp/medax-slurm-test-XXXXXX";
    REQUIRE(::mkdtemp(name));
    state_ = name;
    const Shell started = shell("'" + kScript.string() + "' start '" + state_.string() + "'");
    if (started.code != 0) stop();  // the daemons that did start (the destructor will not run)
    INFO("scripts/slurm-local.sh start: " << started.output);
    REQUIRE(started.code == 0);
    ::setenv("SLURM_CONF", (state_ / "slurm.conf").c_str(), 1);  // for medax, sbatch and squeue
  }
  ~LocalSlurm() {
    stop();
    fs::remove_all(state_);
  }
  void stop() { shell("'" + kScript.string() + "' stop '" + state_.string() + "'"); }

 private:
  fs::path state_;
};

/// Cube jobs through centroid, a sleep, a crash and a count, with a 3 s time limit per job.
std::string experiment(const std::string& sweep) {
  return "name: slurm_test\ninputs: [" + data_file("cube.off") +
         "]\nseed: 3\nlimits: {timeout: 3}\ntable: [test_count.vertices, test_crash.survived]\nstages:\n  - plugin: test_centroid\n  - plugin: test_sleep\n"
         "  - plugin: test_crash\n  - plugin: test_count\noutputs:\n  medial: [ma]\nsweep:\n" + sweep;
}

/// results.csv without the columns that measure time or memory: one line per job.
std::vector<std::string> untimed_rows(const fs::path& csv) {
  std::istringstream in(read_text(csv));
  std::vector<std::vector<std::string>> table;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    table.push_back(cells);
  }
  REQUIRE_FALSE(table.empty());
  std::vector<std::string> rows;
  for (const auto& row : table) {
    std::string kept;
    for (std::size_t i = 0; i < row.size() && i < table[0].size(); ++i)
      if (table[0][i].rfind("time.", 0) != 0 && table[0][i] != "peak_memory_mib") kept += row[i] + ",";
    rows.push_back(kept);
  }
  return rows;
}

nlohmann::json status_of(const fs::path& out, const std::string& job) {
  return nlohmann::json::parse(read_text(out / "jobs" / job / "status.json"));
}

/// Job folder name -> its status and error, and the files of its run folder. A killed job's
/// staging folder (NAME.partial-PID) counts as NAME.partial.
std::map<std::string, std::string> job_summaries(const fs::path& out) {
  std::map<std::string, std::string> jobs;
  for (const auto& entry : fs::directory_iterator(out / "jobs")) {
    const std::string name = entry.path().filename().string();
    if (const auto partial = name.find(".partial-"); partial != std::string::npos) {
      jobs[name.substr(0, partial) + ".partial"] = "staging folder";
      continue;
    }
    const nlohmann::json status = status_of(out, entry.path().filename().string());
    std::set<std::string> files;
    for (const auto& f : fs::directory_iterator(entry.path())) files.insert(f.path().filename().string());
    std::string text = status.value("status", "?") + " | " + status.value("error", "") + " |";
    for (const std::string& f : files) text += " " + f;
    jobs[entry.path().filename().string()] = text;
  }
  return jobs;
}

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

}  // namespace

TEST_CASE("a sweep on Slurm gives the local backend's results, job folders and statuses", "[slurm]") {
  const auto dir = scratch_dir("slurm_sweep");
  const auto file = write_text(dir / "sweep.yaml", experiment("  test_sleep.seconds: [0, 30]\n  test_crash.crash: [false, true]\n"));
  const fs::path local = dir / "local", cluster = dir / "slurm";
  REQUIRE(run_medax("run " + quoted(file) + " -j 2 --out " + quoted(local), kPlugins, dir).code == 1);

  LocalSlurm slurm;
  const auto r = run_medax("run " + quoted(file) + " --backend slurm --poll 0.5 --out " + quoted(cluster), kPlugins, dir);
  INFO(r.out << r.err);
  CHECK(r.code == 1);  // as local: some jobs failed
  CHECK_THAT(r.err, Catch::Contains("submitted 4 job(s) as Slurm array"));
  CHECK_THAT(r.err, Catch::Contains("4/4 done, 3 failed"));
  CHECK(untimed_rows(cluster / "results.csv") == untimed_rows(local / "results.csv"));
  CHECK(job_summaries(cluster) == job_summaries(local));
  const auto statuses = job_summaries(cluster);
  CHECK_THAT(statuses.at("0001-cube-seconds=0-crash=false"), Catch::StartsWith("ok | "));
  CHECK_THAT(statuses.at("0002-cube-seconds=0-crash=true"), Catch::StartsWith("crashed | killed by signal 6"));
  CHECK_THAT(statuses.at("0003-cube-seconds=30-crash=false"), Catch::StartsWith("timeout | killed after the 3 s time limit"));
  // The sweep's 3 s timeout became the array's --time: 3 s + a minute for start-up, in minutes.
  CHECK(nlohmann::json::parse(read_text(cluster / "slurm" / "array.json")).value("time", "") == "0:02:00");
  CHECK(read_text(cluster / "results.md") == read_text(local / "results.md"));


  // Re-submission sends only the failed jobs; --no-wait returns; --results-only collects.
  {
    const auto again = run_medax("run " + quoted(file) + " --backend slurm --no-wait --out " + quoted(cluster), kPlugins, dir);
    INFO(again.err);
    REQUIRE(again.code == 0);
    CHECK_THAT(again.err, Catch::Contains("1 of 4 jobs already finished: skipped"));
    CHECK_THAT(again.err, Catch::Contains("submitted 3 job(s)"));
    const nlohmann::json array = nlohmann::json::parse(read_text(cluster / "slurm" / "array.json"));
    CHECK(array["jobs"].size() == 3);
    CHECK_FALSE(array.value("settled", true));
    for (int i = 0; i < 200 && shell("squeue -h -j " + array.value("array_id", "")).output.size() > 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    const auto collected = run_medax("run " + quoted(file) + " --results-only --out " + quoted(cluster), kPlugins, dir);
    INFO(collected.err);
    CHECK(collected.code == 0);
    CHECK(untimed_rows(cluster / "results.csv") == untimed_rows(local / "results.csv"));
    CHECK(job_summaries(cluster) == job_summaries(local));
  }

  // A request the cluster cannot meet: sbatch's error and what to change.
  {
    const auto refused = run_medax("run " + quoted(file) + " --backend slurm --partition nope --out " +
                                       quoted(dir / "refused"), kPlugins, dir);
    CHECK(refused.code == 1);
    CHECK_THAT(refused.err, Catch::Contains("Invalid partition name specified"));
    CHECK_THAT(refused.err, Catch::Contains("choose another --partition"));
  }

  // A cluster that is down: sbatch's error and what to do.
  {
    slurm.stop();
    write_text(dir / "one.yaml", experiment("  test_sleep.seconds: [0]\n"));
    const auto down = run_medax("run " + quoted(dir / "one.yaml") + " --backend slurm --out " + quoted(dir / "down"),
                                kPlugins, dir);
    CHECK(down.code == 1);
    CHECK_THAT(down.err, Catch::Contains("sbatch failed"));
    CHECK_THAT(down.err, Catch::Contains("scripts/slurm-local.sh start"));
  }
}

TEST_CASE("a task Slurm kills at its own time limit is recorded as a time-out, the others untouched", "[slurm]") {
  const auto dir = scratch_dir("slurm_timeout");
  const auto file = write_text(dir / "sweep.yaml", experiment("  test_sleep.seconds: [0, 300]\n"));
  LocalSlurm slurm;
  // --time 1 (one minute, Slurm's smallest) is shorter than the sweep's own limit would allow
  // (--timeout 0: none), so Slurm's SIGTERM ends the sleeping job after 60-90 s.
  const auto r = run_medax("run " + quoted(file) + " --timeout 0 --backend slurm --time 1 --poll 1 --out " +
                               quoted(dir / "out"), kPlugins, dir);
  INFO(r.out << r.err);
  CHECK(r.code == 1);
  CHECK(status_of(dir / "out", "0001-cube-seconds=0").value("status", "") == "ok");
  const nlohmann::json killed = status_of(dir / "out", "0002-cube-seconds=300");
  CHECK(killed.value("status", "") == "timeout");
  CHECK(killed.value("error", "") == "killed by Slurm at the task's time limit (1:00)");
  CHECK(killed.value("slurm_state", "") == "TIMEOUT");  // from squeue: what --retry looks for
}

TEST_CASE("without sbatch on PATH, --backend slurm says what to do", "[slurm]") {
  const auto dir = scratch_dir("slurm_missing");
  const auto file = write_text(dir / "sweep.yaml", experiment("  test_sleep.seconds: [0]\n"));
  const auto r = run_medax("run " + quoted(file) + " --backend slurm --out " + quoted(dir / "out"), kPlugins + "' PATH='/nonexistent",
                           dir);
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains("sbatch not found"));
  CHECK_THAT(r.err, Catch::Contains("without --backend slurm the sweep runs on this machine"));
}

TEST_CASE("Slurm's duration texts are read as seconds, and limits written in whole minutes", "[slurm]") {
  using medax::slurm::duration_seconds;
  CHECK(duration_seconds("30") == 1800);  // a lone number is minutes, as in --time
  CHECK(duration_seconds("5:00") == 300);
  CHECK(duration_seconds("1:00:00") == 3600);
  CHECK(duration_seconds("2-12") == 2 * 86400 + 12 * 3600);
  CHECK(duration_seconds("0-12") == 12 * 3600);
  CHECK(duration_seconds("1-00:30") == 86400 + 1800);
  CHECK(duration_seconds("1-02:03:04") == 86400 + 2 * 3600 + 3 * 60 + 4);
  CHECK_FALSE(duration_seconds("UNLIMITED"));
  CHECK_FALSE(duration_seconds("NOT_SET"));
  CHECK_FALSE(duration_seconds("1::00"));
  CHECK_FALSE(duration_seconds("-5"));
  CHECK(medax::slurm::time_text(3 + 60) == "0:02:00");  // rounded up: Slurm counts minutes
  CHECK(medax::slurm::time_text(3600) == "1:00:00");
  CHECK(medax::slurm::time_text(2 * 86400) == "48:00:00");
}
