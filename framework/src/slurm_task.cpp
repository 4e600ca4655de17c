// One task of a sweep's Slurm job array: the job on line $SLURM_ARRAY_TASK_ID of the tasks file,
// run exactly as the local runner runs it (its own process, the sweep's limits, status.json).
#include "json_file.hpp"
#include "slurm_commands.hpp"
#include "sweep_backend.hpp"

#include <medax/kernel/registry.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>

namespace medax {

namespace fs = std::filesystem;

namespace {

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

std::string job_name_on_line(const fs::path& tasks_file, std::size_t index) {
  std::ifstream in(tasks_file);
  std::string line;
  for (std::size_t i = 0; std::getline(in, line); ++i)
    if (i == index) return line;
  throw std::runtime_error(fmt::format("{} has no line {} (task index {}): was it rewritten after the array was "
                                       "submitted?", tasks_file.string(), index + 1, index));
}

/// When Slurm ends this task (squeue's time left), so its SIGTERM there reads as a time-out.
std::optional<detail::TaskLimit> slurm_time_limit() {
  // ARRAY_INDEX names this task alone (the array's own id would list every task).
  const std::string task = environment("SLURM_ARRAY_JOB_ID") + "_" + environment("SLURM_ARRAY_TASK_ID");
  const slurm::CommandResult r = slurm::run_command({"squeue", "-h", "-j", task, "-o", "%L|%l"});
  std::string line;  // TIME_LEFT|TIME_LIMIT
  for (const std::string& l : slurm::lines_of(r.output))
    if (l.find('|') != std::string::npos) line = l;
  const auto bar = line.find('|');
  if (r.exit_code != 0 || bar == std::string::npos) return std::nullopt;
  const auto left = slurm::duration_seconds(line.substr(0, bar));
  if (!left) return std::nullopt;
  std::string limit = line.substr(bar + 1);
  limit.erase(limit.find_last_not_of(' ') + 1);
  return detail::TaskLimit{std::chrono::steady_clock::now() + std::chrono::seconds(static_cast<long>(*left)), limit};
}

/// OUT/slurm/started/ARRAY_INDEX: where and when the task began, for a task that ends without a
/// status.json (killed outright) when Slurm no longer remembers why.
void write_started_marker(const fs::path& out_dir, const std::string& job_name) {
  const fs::path dir = out_dir / "slurm" / "started";
  fs::create_directories(dir);
  char host[256] = "?";
  ::gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json marker{{"job", job_name}, {"host", host}, {"started", when}, {"slurm_job_id", environment("SLURM_JOB_ID")}};
  detail::write_json_file(dir / (environment("SLURM_ARRAY_JOB_ID") + "_" + environment("SLURM_ARRAY_TASK_ID")),
                          marker);
}

/// A job that cannot even be validated on the node (a plugin missing there): failed, with why.
void record_invalid(const SweepJob& job, const fs::path& dir, const PipelineError& e) {
  std::string error;
  for (const Diagnostic& d : e.diagnostics()) error += (error.empty() ? "" : " | ") + d.format();
  char host[256] = "?";
  ::gethostname(host, sizeof host - 1);
  fs::create_directories(dir);
  detail::write_json_file(dir / "status.json", {{"input", job.input.string()},
                                                {"settings", job.settings},
                                                {"status", "failed"},
                                                {"error", fmt::format("invalid on node {}: {}", host, error)}});
}

}  // namespace

int run_slurm_task(const SweepConfig& config, std::vector<SweepJob> jobs, const SweepOptions& options,
                   const fs::path& tasks_file) {
  const std::string index = environment("SLURM_ARRAY_TASK_ID");
  if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("--slurm-task runs inside a Slurm array task (SLURM_ARRAY_TASK_ID is not set); "
                             "`medax run FILE --backend slurm` submits them");
  const std::string name = job_name_on_line(tasks_file, std::stoul(index));
  const auto it = std::find_if(jobs.begin(), jobs.end(), [&](const SweepJob& j) { return j.name == name; });
  if (it == jobs.end())
    throw std::runtime_error(fmt::format("job {} is not in {} any more: the experiment changed after the array "
                                         "was submitted; submit again", name, config.file.string()));
  std::vector<SweepJob> job{*it};
  write_started_marker(options.out_dir, name);
  try {
    validate_sweep(config, job, Registry::global());  // sets its config_hash
  } catch (const PipelineError& e) {
    record_invalid(job[0], options.out_dir / "jobs" / name, e);
    return 1;
  }
  return detail::run_job_as_task(config, job[0], options, slurm_time_limit()) == "ok" ? 0 : 1;
}

}  // namespace medax
