// `medax run --backend slurm`: the jobs still to run go to Slurm as one job array; each task runs
// its job as the local runner does (slurm_task.cpp), so the run folders, status.json and results
// are the local backend's. OUT/slurm/ holds the submission: array.json (the latest array and its
// jobs, one per task index), submit-N.tasks/.sh, logs/ARRAY_INDEX.out and started/ markers.
#include "json_file.hpp"
#include "run_context.hpp"
#include "slurm_commands.hpp"
#include "sweep_backend.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <thread>

namespace medax {

namespace fs = std::filesystem;

namespace {

/// The latest array submitted for this run folder (OUT/slurm/array.json).
struct Submission {
  std::string array_id;
  std::vector<std::string> jobs;  ///< job name of each task index
  std::string time, memory;       ///< what the array asked for ("": the partition's default)
  bool settled = false;           ///< finished and every task's end recorded
};

fs::path submission_file(const fs::path& out_dir) { return out_dir / "slurm" / "array.json"; }

std::optional<Submission> read_submission(const fs::path& out_dir) {
  const nlohmann::json j = detail::read_json_file(submission_file(out_dir));
  if (!j.is_object() || !j.contains("array_id")) return std::nullopt;
  return Submission{j.value("array_id", ""), j.value("jobs", std::vector<std::string>{}), j.value("time", ""),
                    j.value("memory", ""), j.value("settled", false)};
}

void write_submission(const fs::path& out_dir, const Submission& s) {
  detail::write_json_file(submission_file(out_dir), {{"array_id", s.array_id},
                                                     {"jobs", s.jobs},
                                                     {"time", s.time},
                                                     {"memory", s.memory},
                                                     {"settled", s.settled}});
}

std::string shell_quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// --time: the user's; else the sweep's timeout plus a minute for the task's start (the task
/// enforces the timeout itself, as the local runner does); else the partition's default.
std::string array_time(const SweepConfig& config, const SlurmOptions& slurm) {
  if (!slurm.time.empty()) return slurm.time;
  return config.limits.timeout_seconds > 0 ? slurm::time_text(config.limits.timeout_seconds + 60) : "";
}

/// --mem: the user's; else the sweep's memory_mib (an address-space limit, which bounds the
/// resident memory Slurm counts); else the partition's default.
std::string array_memory(const SweepConfig& config, const SlurmOptions& slurm) {
  if (!slurm.memory.empty()) return slurm.memory;
  return config.limits.memory_mib > 0 ? fmt::format("{}M", std::ceil(config.limits.memory_mib)) : "";
}

/// Writes OUT/slurm/submit-N.tasks (one job name per task index) and submit-N.sh (the batch
/// script: `medax run ... --slurm-task TASKS`); returns the script.
fs::path write_batch_files(const fs::path& out_dir, const std::vector<std::string>& names,
                           const SweepOptions& options, const SlurmOptions& slurm) {
  const fs::path dir = fs::absolute(out_dir / "slurm");
  fs::create_directories(dir / "logs");
  int n = 1;
  while (fs::exists(dir / fmt::format("submit-{}.tasks", n))) ++n;
  const fs::path tasks = dir / fmt::format("submit-{}.tasks", n);
  std::ofstream(tasks) << fmt::format("{}\n", fmt::join(names, "\n"));
  const fs::path script = dir / fmt::format("submit-{}.sh", n);
  std::ofstream out(script);
  out << "#!/bin/sh\n# Written by `medax run --backend slurm`: array task I runs the job on line I+1 of "
      << tasks.filename().string() << ".\n";
  if (const char* plugins = std::getenv("MEDAX_PLUGIN_PATH")) out << "export MEDAX_PLUGIN_PATH=" << shell_quoted(plugins) << "\n";
  out << "exec " << shell_quoted(options.medax_executable.string());
  for (const std::string& a : slurm.task_args) out << ' ' << shell_quoted(a);
  out << " --out " << shell_quoted(fs::absolute(options.out_dir).string()) << " --quiet --slurm-task "
      << shell_quoted(tasks.string()) << "\n";
  out.close();
  fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add);
  return script;
}

Submission submit(const SweepConfig& config, const std::vector<std::string>& names, const SweepOptions& options,
                  const SlurmOptions& slurm, const std::string& time, const std::string& memory) {
  const fs::path script = write_batch_files(options.out_dir, names, options, slurm);
  std::vector<std::string> argv{"sbatch", "--parsable", "--job-name=medax-" + config.name,
                                "--output=" + (script.parent_path() / "logs" / "%A_%a.out").string(),
                                fmt::format("--array=0-{}{}", names.size() - 1,
                                            slurm.max_parallel > 0 ? fmt::format("%{}", slurm.max_parallel) : "")};
  if (!slurm.partition.empty()) argv.push_back("--partition=" + slurm.partition);
  if (!time.empty()) argv.push_back("--time=" + time);
  if (!memory.empty()) argv.push_back("--mem=" + memory);
  if (slurm.cpus > 0) argv.push_back(fmt::format("--cpus-per-task={}", slurm.cpus));
  argv.push_back(script.string());
  const slurm::CommandResult r = slurm::run_command(argv);
  if (r.exit_code == 0)  // --parsable prints ID[;CLUSTER], after any warnings on stderr
    for (const std::string& line : slurm::lines_of(r.output)) {
      const std::string id = line.substr(0, line.find(';'));
      if (!id.empty() && id.find_first_not_of("0123456789") == std::string::npos)
        return Submission{id, names, time, memory, false};
    }
  throw std::runtime_error(slurm::command_failure("sbatch", r));
}

/// A text field of a job's status.json; "" when the file or the field is missing.
std::string status_field(const fs::path& out_dir, const std::string& name, const char* key) {
  const nlohmann::json status = detail::read_json_file(out_dir / "jobs" / name / "status.json");
  return status.is_object() && status.contains(key) && status[key].is_string() ? status[key].get<std::string>() : "";
}

struct Counts {
  std::size_t pending = 0, running = 0, done = 0, failed = 0;
};

Counts count(const Submission& s, const std::map<std::size_t, std::string>& states, const fs::path& out_dir) {
  Counts c;
  for (const auto& [index, state] : states) {
    if (state == "PENDING") ++c.pending;
    else if (!slurm::is_final_state(state)) ++c.running;
  }
  for (const std::string& name : s.jobs) {
    const std::string state = status_field(out_dir, name, "status");
    if (state.empty()) continue;
    ++c.done;
    if (state != "ok") ++c.failed;
  }
  return c;
}

/// Sleeps `seconds` unless Ctrl-C/SIGTERM comes first; false then.
bool pause(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (detail::interrupt_requested()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return !detail::interrupt_requested();
}

/// Polls squeue (sacct once the controller forgot the array) until no task is pending or running,
/// printing a line whenever the counts change. Returns the tasks' final states; nullopt when
/// interrupted. Three polls in a row where Slurm knows nothing of the array end the wait.
std::optional<std::map<std::size_t, std::string>> wait_for(const Submission& s, const fs::path& out_dir,
                                                           const SweepOptions& options, const SlurmOptions& slurm) {
  std::string shown;
  for (int unknown = 0;;) {
    std::size_t active = 0;
    const auto states = slurm::array_task_states(s.array_id, active);
    const Counts c = count(s, states, out_dir);
    const std::string line = fmt::format("[sweep] slurm array {}: {} pending, {} running; {}/{} done, {} failed",
                                         s.array_id, c.pending, c.running, c.done, s.jobs.size(), c.failed);
    if (!options.quiet && line != shown) fmt::print(stderr, "{}\n", line);
    shown = line;
    unknown = states.empty() ? unknown + 1 : 0;
    if ((!states.empty() && active == 0) || unknown >= 3) return states;
    if (!pause(slurm.poll_seconds)) return std::nullopt;
  }
}

/// A status and its error, for status.json.
using Ending = std::pair<std::string, std::string>;

/// A Slurm state that says why Slurm ended a task: the status and error to record.
std::optional<Ending> slurm_cause(const std::string& state, const Submission& s) {
  if (state == "TIMEOUT")
    return Ending{"timeout", fmt::format("killed by Slurm at the task's time limit ({})",
                                            s.time.empty() ? "the partition's default" : s.time)};
  if (state == "OUT_OF_MEMORY")
    return Ending{"memory", fmt::format("killed by Slurm: over the task's memory ({})",
                                           s.memory.empty() ? "the partition's default" : "--mem " + s.memory)};
  if (state == "NODE_FAIL") return Ending{"node_fail", "the node running the task failed (Slurm NODE_FAIL)"};
  return std::nullopt;
}

/// The status of a task that ended without writing status.json (killed outright).
Ending lost_task(const std::string& state, const Submission& s, std::size_t index,
                                              const fs::path& out_dir) {
  if (auto cause = slurm_cause(state, s)) return *cause;
  const std::string task = fmt::format("{}_{}", s.array_id, index);
  const std::string log = (out_dir / "slurm" / "logs" / (task + ".out")).string();
  if (state.rfind("CANCELLED", 0) == 0 || state == "PREEMPTED")
    return {"interrupted", fmt::format("Slurm {} the task before the job recorded its end (log: {})",
                                       state == "PREEMPTED" ? "preempted" : "cancelled", log)};
  if (!state.empty())
    return {"failed", fmt::format("the task ended ({}) without recording the job's end (log: {})", state, log)};
  const nlohmann::json started = detail::read_json_file(out_dir / "slurm" / "started" / task);
  if (!started.is_object()) return {"", ""};  // never started, and Slurm forgot it: not run
  return {"failed", fmt::format("the task started on {} at {} and was killed without recording the job's end: "
                                "Slurm's time or memory limit or a node failure (Slurm no longer says which: "
                                "no accounting); log: {}",
                                started.value("host", "?"), started.value("started", "?"), log)};
}

/// The status.json of a job Slurm ended, or nullopt to leave the job's own record as it is. A
/// job that recorded its end keeps it unless Slurm killed it (time, memory, node): then the cause
/// is Slurm's, and `slurm_state` marks it for --retry. A job with no record gets one from
/// Slurm's state or the task's start marker.
std::optional<nlohmann::json> slurm_record(nlohmann::json status, const SweepJob& job, const std::string& state,
                                           const Submission& s, std::size_t index, const fs::path& out_dir) {
  const auto cause = slurm_cause(state, s);
  if (status.is_object()) {
    if (!cause || status.contains("slurm_state") || status.value("status", "") == "ok") return std::nullopt;
    if (status.value("status", "") != cause->first) {  // e.g. `crashed` by the OOM killer's SIGKILL
      status["status"] = cause->first;
      status["error"] = cause->second;
    }
    status["slurm_state"] = state;
    return status;
  }
  const auto [what, error] = lost_task(state, s, index, out_dir);
  if (what.empty()) return std::nullopt;
  status = {{"input", job.input.string()}, {"settings", job.settings}, {"config_hash", job.config_hash},
            {"status", what}, {"error", error}};
  if (!state.empty()) status["slurm_state"] = state;
  return status;
}

/// Records every task of a finished array (slurm_record) and marks the array collected.
void settle(Submission& s, const std::map<std::size_t, std::string>& states, const std::vector<SweepJob>& jobs,
            const fs::path& out_dir) {
  std::map<std::string, const SweepJob*> by_name;
  for (const SweepJob& job : jobs) by_name[job.name] = &job;
  for (std::size_t i = 0; i < s.jobs.size(); ++i) {
    const auto job = by_name.find(s.jobs[i]);
    if (job == by_name.end()) continue;  // no longer in the experiment
    const auto found = states.find(i);
    const fs::path file = out_dir / "jobs" / s.jobs[i] / "status.json";
    const auto status = slurm_record(detail::read_json_file(file), *job->second,
                                     found == states.end() ? "" : found->second, s, i, out_dir);
    if (!status) continue;
    fs::create_directories(file.parent_path());
    detail::write_json_file(file, *status);
  }
  s.settled = true;
  write_submission(out_dir, s);
}

/// Waits for an array and records its tasks; false when interrupted.
bool finish(Submission& s, const std::vector<SweepJob>& jobs, const SweepOptions& options, const SlurmOptions& slurm) {
  const auto states = wait_for(s, options.out_dir, options, slurm);
  if (!states) return false;
  settle(s, *states, jobs, options.out_dir);
  return true;
}

/// Jobs of `s` that Slurm killed at its time or memory limit: what a retry runs again.
std::vector<std::string> killed_for_limits(const Submission& s, const fs::path& out_dir, bool& time, bool& memory) {
  std::vector<std::string> names;
  time = memory = false;
  for (const std::string& name : s.jobs) {
    const std::string state = status_field(out_dir, name, "slurm_state");
    if (state != "TIMEOUT" && state != "OUT_OF_MEMORY") continue;
    (state == "TIMEOUT" ? time : memory) = true;
    names.push_back(name);
  }
  return names;
}

/// Twice a --mem value (NUMBER[K|M|G|T], megabytes without a unit).
std::string doubled_memory(const std::string& memory) {
  const std::size_t digits = memory.find_first_not_of("0123456789");
  if (digits == 0 || memory.empty()) return memory;
  return fmt::format("{}{}", 2 * std::stoull(memory.substr(0, digits)), memory.substr(std::min(digits, memory.size())));
}

void count_results(const std::vector<std::string>& names, const fs::path& out_dir, SweepSummary& summary) {
  for (const std::string& name : names) {
    const std::string state = status_field(out_dir, name, "status");
    if (state == "ok") ++summary.succeeded;
    else if (state == "interrupted") ++summary.interrupted;
    else if (!state.empty()) ++summary.failed;
  }
}

/// Resubmits, up to `slurm.retries` times, the jobs Slurm killed at its time or memory limit, with
/// twice that limit. Returns false when interrupted.
bool retry_killed(Submission& s, const SweepConfig& config, const std::vector<SweepJob>& jobs,
                  const SweepOptions& options, const SlurmOptions& slurm) {
  for (int round = 0; round < slurm.retries; ++round) {
    bool time = false, memory = false;
    const std::vector<std::string> names = killed_for_limits(s, options.out_dir, time, memory);
    const auto seconds = slurm::duration_seconds(s.time);
    if (names.empty() || (time && !seconds) || (memory && s.memory.empty())) {
      if (!names.empty() && !options.quiet)
        fmt::print(stderr, "[sweep] no retry: the limit Slurm killed the jobs at is the partition's default; "
                           "give --time/--mem to retry with twice it\n");
      return true;
    }
    const std::string next_time = time ? slurm::time_text(2 * *seconds) : s.time;
    const std::string next_memory = memory ? doubled_memory(s.memory) : s.memory;
    for (const std::string& name : names) fs::remove(options.out_dir / "jobs" / name / "status.json");
    s = submit(config, names, options, slurm, next_time, next_memory);
    write_submission(options.out_dir, s);
    if (!options.quiet)
      fmt::print(stderr, "[sweep] retry {}: {} job(s) killed by Slurm's limit resubmitted as array {} (--time {}, --mem {})\n",
                 round + 1, names.size(), s.array_id, next_time.empty() ? "default" : next_time,
                 next_memory.empty() ? "default" : next_memory);
    if (!finish(s, jobs, options, slurm)) return false;
  }
  return true;
}

void print_stopped_waiting(const Submission& s) {
  fmt::print(stderr, "[sweep] stopped waiting: array {} keeps running on the cluster (`scancel {}` stops it); the "
                     "same command waits for it again, `--results-only` collects what has finished\n",
             s.array_id, s.array_id);
}

/// An array an earlier command submitted (--no-wait) and nobody collected: waited for and
/// recorded, its jobs that ended into `ended` (this command does not send them again). With
/// --no-wait it is only recorded if it has finished. False when this command should stop here:
/// the array still runs under --no-wait, or Ctrl-C stopped the wait (`summary.signal`).
bool collect_earlier(const std::vector<SweepJob>& jobs, const SweepOptions& options, const SlurmOptions& slurm,
                     SweepSummary& summary, std::vector<std::string>& ended) {
  std::optional<Submission> earlier = read_submission(options.out_dir);
  if (!earlier || earlier->settled) return true;
  if (!slurm.wait) {
    std::size_t active = 0;
    const auto states = slurm::array_task_states(earlier->array_id, active);
    if (active > 0) {
      fmt::print(stderr, "[sweep] array {} submitted earlier still has {} task(s) pending or running: nothing "
                 "submitted (run without --no-wait to wait for it and then submit what is missing)\n",
                 earlier->array_id, active);
      return false;
    }
    settle(*earlier, states, jobs, options.out_dir);
    return true;
  }
  if (!options.quiet) fmt::print(stderr, "[sweep] array {} submitted earlier: waiting for it\n", earlier->array_id);
  if (!finish(*earlier, jobs, options, slurm)) {
    print_stopped_waiting(*earlier);
    summary.signal = detail::interrupt_signal();
    return false;
  }
  for (const std::string& name : earlier->jobs)
    if (!status_field(options.out_dir, name, "status").empty()) ended.push_back(name);
  return true;
}

}  // namespace

SweepSummary run_sweep_on_slurm(const SweepConfig& config, const std::vector<SweepJob>& jobs,
                                const SweepOptions& options, const SlurmOptions& slurm) {
  SweepSummary summary;
  summary.total = jobs.size();
  fs::create_directories(options.out_dir / "jobs");
  detail::install_interrupt_handler();
  std::vector<std::string> ended;  // jobs of an earlier array that ended while this command waited
  if (!collect_earlier(jobs, options, slurm, summary, ended)) return summary;
  const std::set<std::string> just_ended(ended.begin(), ended.end());
  std::vector<std::string> names;
  for (std::size_t i : detail::jobs_to_run(jobs, options.out_dir / "jobs", summary, options.quiet)) {
    if (just_ended.count(jobs[i].name)) continue;
    names.push_back(jobs[i].name);
    fs::create_directories(options.out_dir / "jobs" / jobs[i].name);
    fs::remove(options.out_dir / "jobs" / jobs[i].name / "status.json");
  }
  if (!names.empty()) {
    Submission s = submit(config, names, options, slurm, array_time(config, slurm), array_memory(config, slurm));
    write_submission(options.out_dir, s);
    if (!options.quiet)
      fmt::print(stderr, "[sweep] submitted {} job(s) as Slurm array {}{}{}\n", names.size(), s.array_id,
                 s.time.empty() ? "" : ", --time " + s.time, s.memory.empty() ? "" : ", --mem " + s.memory);
    if (!slurm.wait) return summary;
    if (!finish(s, jobs, options, slurm) || !retry_killed(s, config, jobs, options, slurm)) {
      print_stopped_waiting(s);
      summary.signal = detail::interrupt_signal();
    }
  }
  ended.insert(ended.end(), names.begin(), names.end());
  count_results(ended, options.out_dir, summary);
  write_sweep_results(config, jobs, options.out_dir);
  return summary;
}

std::size_t collect_slurm_results(const SweepConfig& config, const std::vector<SweepJob>& jobs,
                                  const fs::path& out_dir, std::string& note) {
  std::optional<Submission> s = read_submission(out_dir);
  if (s && !s->settled && slurm::run_command({"squeue", "--version"}).exit_code != 0) {
    note = fmt::format("Slurm array {} is not recorded as finished and squeue cannot be asked here: its unfinished "
                       "jobs show as not run; collect where squeue works",
                       s->array_id);
  } else if (s && !s->settled) {
    std::size_t active = 0;
    const auto states = slurm::array_task_states(s->array_id, active);
    if (active > 0)
      note = fmt::format("Slurm array {} still has {} task(s) pending or running: their jobs show as not run", s->array_id,
                         active);
    else
      settle(*s, states, jobs, out_dir);
  }
  return write_sweep_results(config, jobs, out_dir);
}

}  // namespace medax
