// Experiments: sweep expansion, process isolation (a crash and a time-out fail only their job),
// resume, the results table's schema, and plots.
#include "cli_helpers.hpp"

#include <medax/kernel/sweep.hpp>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <map>
#include <set>
#include <thread>

using medax::test::data_file;
using medax::test::plugin_dir;
using medax::test::read_text;
using medax::test::run_medax;
using medax::test::scratch_dir;
using medax::test::spawn_medax;
using medax::test::write_text;

namespace fs = std::filesystem;

namespace {

const std::string kPlugins = plugin_dir("good").string() + ":" + plugin_dir("sweep").string();

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

std::string column(const std::vector<std::string>& header, const std::vector<std::string>& row, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  REQUIRE(it != header.end());
  return row.at(static_cast<std::size_t>(it - header.begin()));
}

/// The results.csv column `name`, one value per job row.
std::vector<std::string> csv_column(const fs::path& csv, const std::string& name) {
  const auto lines = lines_of(read_text(csv));
  REQUIRE(!lines.empty());
  const auto header = csv_cells(lines[0]);
  std::vector<std::string> values;
  for (std::size_t i = 1; i < lines.size(); ++i) values.push_back(column(header, csv_cells(lines[i]), name));
  return values;
}

/// Waits until the log of job `name` contains `text`: in its folder or, while the run writes
/// into a staging folder, in `name.partial-*`.
bool wait_for_job_log(const fs::path& jobs_dir, const std::string& name, const std::string& text,
                      std::chrono::seconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(jobs_dir, ec)) {
      const std::string folder = entry.path().filename().string();
      if (folder != name && folder.rfind(name + ".partial-", 0) != 0) continue;
      const fs::path log = entry.path() / "log.txt";
      if (fs::exists(log, ec) && read_text(log).find(text) != std::string::npos) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

/// The processes whose parent is `parent` (from /proc/PID/stat).
std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> children;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    if (!std::getline(in, stat)) continue;  // gone meanwhile
    const auto close = stat.rfind(')');     // "PID (COMM) STATE PPID ..."; COMM may hold spaces
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));
    std::string state;
    pid_t ppid = 0;
    fields >> state >> ppid;
    if (ppid == parent) children.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return children;
}

}  // namespace

TEST_CASE("a sweep expands to the cartesian product with inputs outermost", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_expand");
  const fs::path file = write_text(dir / "sweep.yaml",
                                   "name: grid\ninputs: [" + data_file("cube.off") + ", " + data_file("ellipsoid.off") +
                                       "]\nsweep:\n  scale.factor: [1, 2, 3]\n  count.element: [all, vertices]\n"
                                       "stages:\n  - {plugin: test_scale, id: scale}\n  - plugin: test_centroid\n"
                                       "  - {plugin: test_count, id: count}\n");
  CHECK(medax::is_sweep(file));
  const medax::SweepConfig config = medax::load_sweep(file);
  auto jobs = medax::expand_sweep(config);
  REQUIRE(jobs.size() == 2 * 3 * 2);
  CHECK(jobs[0].input.filename() == "cube.off");
  CHECK(jobs[0].settings == std::vector<std::string>{"scale.factor=1", "count.element=all"});
  CHECK(jobs[1].settings == std::vector<std::string>{"scale.factor=1", "count.element=vertices"});
  CHECK(jobs[2].settings == std::vector<std::string>{"scale.factor=2", "count.element=all"});
  CHECK(jobs[6].input.filename() == "ellipsoid.off");
  std::set<std::string> names;
  for (const auto& job : jobs) names.insert(job.name);
  CHECK(names.size() == jobs.size());
  CHECK(jobs[0].name == "0001-cube-factor=1-element=all");
  medax::validate_sweep(config, jobs, medax::test::good_registry());
}

TEST_CASE("inputs may be globs and manifests", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_inputs");
  write_text(dir / "list.txt", "# two meshes\n" + data_file("cube.off") + "\n\n" + data_file("sphere.obj") + "\n");
  const fs::path file = write_text(
      dir / "sweep.yaml", "inputs:\n  - " + (fs::path(MEDAX_TEST_DATA_DIR) / "*.off").string() +
                              "\n  - {manifest: list.txt}\nstages:\n  - plugin: test_centroid\n");
  const auto config = medax::load_sweep(file);
  std::vector<std::string> names;
  for (const auto& p : config.inputs) names.push_back(p.filename().string());
  CHECK(names == std::vector<std::string>{"cube.off", "ellipsoid.off", "joint.off", "cube.off", "sphere.obj"});
}

TEST_CASE("sweep errors are found before any job runs", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_errors");
  const fs::path file = write_text(dir / "sweep.yaml", "inputs: [nothing_here.off]\nsweep:\n  scale.factor: [1, -5]\n"
                                                       "stages:\n  - {plugin: test_scale, id: scale}\n");
  CHECK_THROWS_WITH(medax::load_sweep(file), Catch::Contains("sweep.yaml:1:10") && Catch::Contains("not found"));
  write_text(file, "input: " + data_file("cube.off") + "\nsweep:\n  scale.factor: [1, -5]\n  nodot: [1]\n"
                   "stages:\n  - {plugin: test_scale, id: scale}\n");
  CHECK_THROWS_WITH(medax::load_sweep(file), Catch::Contains("sweep.yaml:4:11") && Catch::Contains("a bundle is a map") &&
                                                 !Catch::Contains("no values"));
  write_text(file, "input: " + data_file("cube.off") + "\nsweep:\n  scale.factor: [1, -5]\n"
                   "stages:\n  - {plugin: test_scale, id: scale}\n");
  const auto config = medax::load_sweep(file);
  auto jobs = medax::expand_sweep(config);
  CHECK_THROWS_WITH(medax::validate_sweep(config, jobs, medax::test::good_registry()),
                    Catch::Contains("sweep scale.factor=-5") && Catch::Contains("must be"));
}

TEST_CASE("a key given twice in a sweep file is reported before any job runs", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_duplicate_keys");
  // Without the check the second `scale.factor` axis (and the second `sweep:`) were silently dropped.
  const fs::path file = write_text(dir / "sweep.yaml", "input: " + data_file("cube.off") +
                                                           "\nsweep:\n  scale.factor: [1, 2]\n  scale.factor: [3]\n"
                                                           "stages:\n  - {plugin: test_scale, id: scale}\n"
                                                           "sweep:\n  scale.factor: [4]\n");
  try {
    medax::load_sweep(file);
    FAIL("the sweep loaded without error");
  } catch (const medax::PipelineError& e) {
    std::vector<std::string> found;
    for (const medax::Diagnostic& d : e.diagnostics()) found.push_back(d.format());
    INFO(e.what());
    REQUIRE(found.size() == 2);
    CHECK_THAT(found[0], Catch::Contains("sweep.yaml:4:3") && Catch::Contains("duplicate key 'scale.factor' (first at line 3)"));
    CHECK_THAT(found[1], Catch::Contains("sweep.yaml:7:1") && Catch::Contains("duplicate key 'sweep' (first at line 2)") &&
                             Catch::Contains("remove one"));
  }
  write_text(file, "input: " + data_file("cube.off") + "\nsweep:\n  scale.factor: [1, 2]\n"
                   "stages:\n  - {plugin: test_scale, id: scale}\n");
  CHECK(medax::expand_sweep(medax::load_sweep(file)).size() == 2);
}

TEST_CASE("a crashing job and a timed-out job fail alone and are reported", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_isolation");
  const fs::path file = write_text(
      dir / "sweep.yaml", "name: isolation\ninput: " + data_file("cube.off") +
                              "\nlimits: {timeout: 2}\nsweep:\n  crash.crash: [false, true]\n  sleep.seconds: [0, 30]\n"
                              "stages:\n  - plugin: test_centroid\n  - {plugin: test_crash, id: crash}\n"
                              "  - {plugin: test_sleep, id: sleep}\n");
  const auto r = run_medax("run '" + file.string() + "' -j 2 --out '" + (dir / "out").string() + "'", kPlugins, dir);
  INFO(r.out << r.err);
  CHECK(r.code == 1);  // some jobs failed
  const auto lines = lines_of(read_text(dir / "out" / "results.csv"));
  REQUIRE(lines.size() == 5);
  const auto header = csv_cells(lines[0]);
  std::map<std::string, std::string> status;  // "crash,seconds" -> status
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto row = csv_cells(lines[i]);
    status[column(header, row, "crash.crash") + "," + column(header, row, "sleep.seconds")] =
        column(header, row, "status");
  }
  CHECK(status["false,0"] == "ok");
  CHECK(status["true,0"] == "crashed");
  CHECK(status["false,30"] == "timeout");
  CHECK(status["true,30"] == "crashed");
  CHECK(r.err.find("4/4 done, 3 failed") != std::string::npos);
}

TEST_CASE("a sweep resumes: finished jobs are skipped and failed ones run again", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_resume");
  const fs::path file = write_text(dir / "sweep.yaml", "input: " + data_file("cube.off") +
                                                           "\nsweep:\n  crash.crash: [false, true]\n"
                                                           "stages:\n  - plugin: test_centroid\n"
                                                           "  - {plugin: test_crash, id: crash}\n");
  const std::string command = "run '" + file.string() + "' --out '" + (dir / "out").string() + "'";
  const auto first = run_medax(command, kPlugins, dir);
  CHECK(first.out.find("1 ok, 1 failed, 0 skipped") != std::string::npos);
  const fs::path ok_job = dir / "out" / "jobs" / "0001-cube-crash=false";
  REQUIRE(fs::exists(ok_job / "status.json"));
  const auto stamp = fs::last_write_time(ok_job / "metrics.json");
  const auto second = run_medax(command, kPlugins, dir);
  INFO(second.out << second.err);
  CHECK(second.out.find("0 ok, 1 failed, 1 skipped") != std::string::npos);
  CHECK(fs::last_write_time(ok_job / "metrics.json") == stamp);
}

TEST_CASE("results.csv has one row per job with parameters metrics times and status", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_schema");
  const fs::path file = write_text(
      dir / "sweep.yaml", "name: schema\ninput: " + data_file("cube.off") +
                              "\nsweep:\n  scale.factor: [0.5, 1, 2]\nplots:\n  - {x: scale.factor, y: c.vertices}\n"
                              "table: [scale.factor, c.vertices]\n"
                              "stages:\n  - {plugin: test_scale, id: scale}\n  - plugin: test_centroid\n"
                              "  - {plugin: test_count, id: c}\n");
  const auto r = run_medax("run '" + file.string() + "' --out '" + (dir / "out").string() + "'", kPlugins, dir);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  const auto lines = lines_of(read_text(dir / "out" / "results.csv"));
  REQUIRE(lines.size() == 4);
  const auto header = csv_cells(lines[0]);
  const std::vector<std::string> expected{"job",        "input",        "scale.factor", "status",
                                          "error",      "c.edges",      "c.faces",      "c.vertices",
                                          "peak_memory_mib", "time.c", "time.scale", "time.test_centroid",
                                          "time.total"};
  CHECK(header == expected);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto row = csv_cells(lines[i]);
    CHECK(column(header, row, "status") == "ok");
    CHECK(column(header, row, "c.vertices") == "1");
    CHECK(std::stod(column(header, row, "time.total")) > 0);
  }
  CHECK(column(header, csv_cells(lines[3]), "scale.factor") == "2");
  const std::string md = read_text(dir / "out" / "results.md");
  CHECK(md.find("| job | input | status | scale.factor | c.vertices |\n") != std::string::npos);
  CHECK(md.find("time.total") == std::string::npos);  // results.csv keeps every column
  for (const char* ext : {"png", "svg"}) {
    const fs::path plot = dir / "out" / "plots" / (std::string("c.vertices_vs_scale.factor.") + ext);
    REQUIRE(fs::exists(plot));
    const std::string bytes = read_text(plot);
    CHECK(bytes.find(ext == std::string("png") ? "PNG" : "<svg") != std::string::npos);
  }
}

TEST_CASE("a named sweep axis applies bundles of settings with plugin swaps first", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_bundles");
  const fs::path file = write_text(
      dir / "sweep.yaml", "input: " + data_file("cube.off") +
                              "\nsweep:\n  method:\n    - {name: small, scale.factor: 0.5}\n"
                              "    - {name: oracle, extract.oracle: test_radius_field, extract.plugin: test_oracle_centroid}\n"
                              "stages:\n  - {plugin: test_scale, id: scale}\n  - {plugin: test_centroid, id: extract}\n");
  const auto config = medax::load_sweep(file);
  auto jobs = medax::expand_sweep(config);
  REQUIRE(jobs.size() == 2);
  CHECK(jobs[0].assignment == std::vector<std::pair<std::string, std::string>>{{"method", "small"}});
  CHECK(jobs[0].settings == std::vector<std::string>{"scale.factor=0.5"});
  CHECK(jobs[1].name == "0002-cube-method=oracle");
  CHECK(jobs[1].settings ==
        std::vector<std::string>{"extract.plugin=test_oracle_centroid", "extract.oracle=test_radius_field"});
  medax::validate_sweep(config, jobs, medax::test::good_registry());
}

TEST_CASE("a resumed sweep runs again the jobs whose configuration changed", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_resume_changed");
  const auto sweep_file = [&](const std::string& seconds, const std::string& table) {
    return write_text(dir / "sweep.yaml", "name: changed\ninput: " + data_file("cube.off") +
                                              "\nsweep:\n  c.element: [vertices, all]\n" + table +
                                              "stages:\n  - plugin: test_centroid\n  - {plugin: test_count, id: c}\n"
                                              "  - {plugin: test_sleep, id: nap, params: {seconds: " + seconds + "}}\n");
  };
  const fs::path file = sweep_file("0", "");
  const std::string command = "run '" + file.string() + "' --out '" + (dir / "out").string() + "'";
  const fs::path csv = dir / "out" / "results.csv";
  const auto first = run_medax(command, kPlugins, dir);
  INFO(first.out << first.err);
  REQUIRE(first.code == 0);
  CHECK(csv_column(csv, "nap.slept") == std::vector<std::string>{"0", "0"});
  const std::string status = read_text(dir / "out" / "jobs" / "0001-cube-element=vertices" / "status.json");
  CHECK_THAT(status, Catch::Matches(R"([\s\S]*"config_hash": ?"[0-9a-f]{16}"[\s\S]*)"));

  // Unchanged, or changed only in what the table shows: nothing runs again.
  sweep_file("0", "table: [c.vertices]\n");
  const auto same = run_medax(command, kPlugins, dir);
  INFO(same.out << same.err);
  CHECK(same.out.find("0 ok, 0 failed, 2 skipped as already done)") != std::string::npos);

  // A parameter default edited in the file: both jobs run again with it (before: skipped, and
  // results.csv kept the old value).
  sweep_file("0.01", "");
  const auto edited = run_medax(command, kPlugins, dir);
  INFO(edited.out << edited.err);
  CHECK(edited.code == 0);
  CHECK(edited.out.find("2 ok, 0 failed, 0 skipped as already done, 2 run again as their configuration changed") !=
        std::string::npos);
  CHECK(edited.err.find("2 finished jobs run again: the configuration changed") != std::string::npos);
  CHECK(csv_column(csv, "nap.slept") == std::vector<std::string>{"0.01", "0.01"});
  CHECK(read_text(dir / "out" / "jobs" / "0001-cube-element=vertices" / "status.json") != status);
}

TEST_CASE("SIGTERM or SIGINT of a sweep stops its jobs, records them and writes the results", "[sweep][faults]") {
  for (const int sig : {SIGTERM, SIGINT}) {
    DYNAMIC_SECTION("signal " << sig) {
      const fs::path dir = scratch_dir("sweep_interrupt_" + std::to_string(sig));
      // One job stops on the forwarded signal after its short sleep; test_sleep ignores the
      // signal, so the long one is killed when the 1 s grace runs out.
      const fs::path file = write_text(
          dir / "sweep.yaml", "name: interrupt\ninput: " + data_file("cube.off") +
                                  "\nlimits: {interrupt_grace: 1}\nsweep:\n  nap.seconds: [1, 600]\n"
                                  "stages:\n  - plugin: test_centroid\n  - {plugin: test_sleep, id: nap}\n");
      const fs::path out = dir / "out";
      const std::vector<std::string> jobs{"0001-cube-seconds=1", "0002-cube-seconds=600"};
      const pid_t sweep = spawn_medax({"run", file.string(), "-j", "2", "--out", out.string()}, kPlugins, dir);
      bool started = true;
      for (const std::string& job : jobs)
        started = started && wait_for_job_log(out / "jobs", job, "read ", std::chrono::seconds(60));
      const std::vector<pid_t> job_pids = children_of(sweep);
      ::kill(sweep, started ? sig : SIGKILL);
      int wait_status = 0;
      REQUIRE(::waitpid(sweep, &wait_status, 0) == sweep);
      INFO(read_text(dir / "stdout.txt") << read_text(dir / "stderr.txt"));
      REQUIRE(started);
      CHECK(job_pids.size() == 2);
      REQUIRE(WIFEXITED(wait_status));  // not killed by the signal: it stopped cleanly
      CHECK(WEXITSTATUS(wait_status) == 128 + sig);
      for (const pid_t pid : job_pids) {  // no job left behind, nor anything in its process group
        CHECK(::kill(pid, 0) == -1);
        CHECK(::kill(-pid, 0) == -1);
        CHECK(errno == ESRCH);
      }
      const std::string short_job = read_text(out / "jobs" / jobs[0] / "status.json");
      CHECK((short_job.find("\"status\": \"interrupted\"") != std::string::npos ||
             short_job.find("\"status\": \"ok\"") != std::string::npos));
      const std::string long_job = read_text(out / "jobs" / jobs[1] / "status.json");
      CHECK(long_job.find("\"status\": \"interrupted\"") != std::string::npos);
      CHECK(long_job.find("killed after the 1 s grace") != std::string::npos);
      const auto statuses = csv_column(out / "results.csv", "status");
      REQUIRE(statuses.size() == 2);
      CHECK(statuses[1] == "interrupted");
      CHECK(read_text(dir / "stderr.txt").find("run the same command again to resume") != std::string::npos);

      // Resume: the interrupted jobs run again (here the long one meets a 5 s time limit).
      const auto resumed = run_medax("run '" + file.string() + "' -j 2 --timeout 5 --out '" + out.string() + "'",
                                     kPlugins, dir);
      INFO(resumed.out << resumed.err);
      const auto after = csv_column(out / "results.csv", "status");
      REQUIRE(after.size() == 2);
      CHECK(after[0] == "ok");
      CHECK(after[1] == "timeout");
    }
  }
}

TEST_CASE("a bundle that sets a key another sweep key sets is refused", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_conflict");
  // Without the check the bundle's factor ran while the job folder and results.csv named the swept one.
  const fs::path file = write_text(dir / "sweep.yaml", "input: " + data_file("cube.off") +
                                                           "\nsweep:\n  scale.factor: [1, 2]\n  method:\n"
                                                           "    - {name: big, scale.factor: 3}\n"
                                                           "stages:\n  - {plugin: test_scale, id: scale}\n");
  CHECK_THROWS_WITH(medax::load_sweep(file), Catch::Contains("sweep.yaml:4:3") &&
                                                 Catch::Contains("sweep key 'method' sets scale.factor, which "
                                                                 "'scale.factor' sets too"));
  write_text(file, "input: " + data_file("cube.off") + "\nsweep:\n  scale.factor: [1, 2]\n  method:\n"
                   "    - {name: big, c.plugin: test_count}\n"
                   "stages:\n  - {plugin: test_scale, id: scale}\n  - plugin: test_centroid\n"
                   "  - {plugin: test_count, id: c}\n");
  CHECK(medax::expand_sweep(medax::load_sweep(file)).size() == 2);
}

TEST_CASE("a plot that cannot be drawn is named, and plots of removed entries go", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_plot_warnings");
  const std::string head = "name: plots\ninput: " + data_file("cube.off") +
                           "\nsweep:\n  scale.factor: [0.5, 1]\n  method:\n    - {name: a, c.plugin: test_count}\n";
  const std::string stages =
      "stages:\n  - {plugin: test_scale, id: scale}\n  - plugin: test_centroid\n  - {plugin: test_count, id: c}\n";
  const fs::path file = write_text(dir / "sweep.yaml", head +
                                                           "plots:\n  - {x: method, y: c.vertices}\n"
                                                           "  - {x: scale.factor, y: c.nothing}\n"
                                                           "  - {x: scale.factor, y: c.vertices}\n" + stages);
  const std::string out = (dir / "out").string();
  auto r = run_medax("run '" + file.string() + "' --out '" + out + "'", kPlugins, dir);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("plot of c.vertices against method not drawn: 'method' holds no numbers"));
  CHECK_THAT(r.err, Catch::Contains("plot of c.nothing against scale.factor not drawn: results.csv has no column "
                                    "'c.nothing'"));
  const fs::path kept = dir / "out" / "plots" / "c.vertices_vs_scale.factor.svg";
  REQUIRE(fs::exists(kept));

  write_text(file, head + "plots:\n  - {x: scale.factor, y: time.total}\n" + stages);
  r = run_medax("run '" + file.string() + "' --out '" + out + "' --results-only", kPlugins, dir);
  REQUIRE(r.code == 0);
  CHECK(fs::exists(dir / "out" / "plots" / "time.total_vs_scale.factor.svg"));
  CHECK_FALSE(fs::exists(kept));
}

TEST_CASE("a manifest line's variables fill ${NAME} in the sweep values of that input's jobs", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_variables");
  write_text(dir / "list.txt", "# mesh, then its variables\n" + data_file("cube.off") + " factor=2 what=vertices\n" +
                                   data_file("ellipsoid.off") + "  what=all   factor=0.5  # comment\n");
  const fs::path file = write_text(
      dir / "sweep.yaml", "inputs:\n  - {manifest: list.txt}\nsweep:\n  scale.factor: [1, \"${factor}\"]\n"
                          "  method:\n    - {name: \"n${what}\", count.element: \"${what}\"}\n"
                          "stages:\n  - {plugin: test_scale, id: scale}\n  - plugin: test_centroid\n"
                          "  - {plugin: test_count, id: count}\n");
  const auto config = medax::load_sweep(file);
  REQUIRE(config.inputs.size() == 2);
  const auto& cube = config.variables.at(config.inputs[0]);
  CHECK(cube.values == std::map<std::string, std::string>{{"factor", "2"}, {"what", "vertices"}});
  CHECK(cube.origin == (dir / "list.txt").string() + ":2");
  auto jobs = medax::expand_sweep(config);
  REQUIRE(jobs.size() == 4);
  CHECK(jobs[0].settings == std::vector<std::string>{"scale.factor=1", "count.element=vertices"});
  CHECK(jobs[1].settings == std::vector<std::string>{"scale.factor=2", "count.element=vertices"});
  CHECK(jobs[1].assignment == std::vector<std::pair<std::string, std::string>>{{"scale.factor", "2"}, {"method", "nvertices"}});
  CHECK(jobs[1].name == "0002-cube-factor=2-method=nvertices");
  CHECK(jobs[3].settings == std::vector<std::string>{"scale.factor=0.5", "count.element=all"});
  medax::validate_sweep(config, jobs, medax::test::good_registry());
  CHECK(jobs[1].config_hash != jobs[3].config_hash);
}

TEST_CASE("an unknown or malformed sweep variable is reported with the file and line of each side", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_variable_errors");
  const fs::path list = write_text(dir / "list.txt", data_file("cube.off") + " factor=2\n" + data_file("ellipsoid.off") + "\n");
  const fs::path file = write_text(dir / "sweep.yaml", "inputs:\n  - {manifest: list.txt}\n  - " + data_file("joint.off") +
                                                           "\nsweep:\n  scale.factor: [\"${factor}\"]\n"
                                                           "  count.element: [\"${1x}\"]\n"
                                                           "stages:\n  - {plugin: test_scale, id: scale}\n"
                                                           "  - {plugin: test_count, id: count}\n");
  try {
    medax::load_sweep(file);
    FAIL("the sweep loaded without error");
  } catch (const medax::PipelineError& e) {
    INFO(e.what());
    REQUIRE(e.diagnostics().size() == 2);
    const std::string unknown = e.diagnostics()[0].format();
    CHECK_THAT(unknown, Catch::Contains("sweep.yaml:5:18") && Catch::Contains("unknown variable '${factor}'") &&
                            Catch::Contains("ellipsoid.off (" + list.string() + ":2)") &&
                            Catch::Contains("joint.off (not from a manifest line") && !Catch::Contains("cube.off") &&
                            Catch::Contains("write `factor=VALUE`"));
    CHECK_THAT(e.diagnostics()[1].format(), Catch::Contains("sweep.yaml:6:19") && Catch::Contains("written ${NAME}"));
  }
  write_text(list, data_file("cube.off") + " factor=2 factor=3\n");
  CHECK_THROWS_WITH(medax::load_sweep(file), Catch::Contains(list.string() + ":1: variable 'factor' is given twice"));

  // An input replaced after loading (`medax run FILE --input MESH`) keeps its manifest variables
  // when it is listed there, and is refused naming the variable otherwise.
  write_text(list, data_file("cube.off") + " factor=2\n");
  write_text(file, "inputs:\n  - {manifest: list.txt}\nsweep:\n  scale.factor: [\"${factor}\"]\n"
                   "stages:\n  - {plugin: test_scale, id: scale}\n");
  auto config = medax::load_sweep(file);
  CHECK(medax::expand_sweep(config).at(0).settings == std::vector<std::string>{"scale.factor=2"});
  config.inputs = {fs::path(data_file("sphere.obj"))};
  CHECK_THROWS_WITH(medax::expand_sweep(config), Catch::Contains("unknown variable '${factor}'") &&
                                                     Catch::Contains("sphere.obj (not from a manifest line"));

  // ${NAME:-DEFAULT}: the default serves only inputs that do not set NAME.
  write_text(file, "inputs:\n  - {manifest: list.txt}\nsweep:\n  scale.factor: [\"${factor:-3}\"]\n"
                   "stages:\n  - {plugin: test_scale, id: scale}\n");
  config = medax::load_sweep(file);
  CHECK(medax::expand_sweep(config).at(0).settings == std::vector<std::string>{"scale.factor=2"});
  config.inputs = {fs::path(data_file("sphere.obj"))};
  const auto jobs = medax::expand_sweep(config);
  CHECK(jobs.at(0).settings == std::vector<std::string>{"scale.factor=3"});
  CHECK(jobs.at(0).name == "0001-sphere-factor=3");
}

TEST_CASE("a bad --set on an experiment is named as --set, a bad swept value as sweep", "[sweep]") {
  const fs::path dir = scratch_dir("sweep_set_origin");
  const fs::path file = write_text(dir / "sweep.yaml", "input: " + data_file("cube.off") +
                                                           "\nsweep:\n  scale.factor: [1, -5]\n"
                                                           "stages:\n  - {plugin: test_scale, id: scale}\n"
                                                           "  - plugin: test_centroid\n");
  const auto r = run_medax("validate '" + file.string() + "' --set test_centroid.points=nowhere", kPlugins, dir);
  INFO(r.out << r.err);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("--set test_centroid.points=nowhere: error"));
  CHECK_THAT(r.err, !Catch::Contains("sweep test_centroid.points"));
  CHECK_THAT(r.err, Catch::Contains("sweep scale.factor=-5: error"));
}
