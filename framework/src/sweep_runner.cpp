// Runs sweep jobs, each in its own `medax run --job` process, a few at a time, with per-job
// time and memory limits. A job's status.json records how it ended; a finished job is skipped
// when the sweep runs again with the same configuration. Ctrl-C/SIGTERM of the sweep is
// forwarded to the running jobs, which are waited for and recorded as interrupted.
#include <medax/io.hpp>
#include <medax/kernel/sweep.hpp>

#include "run_context.hpp"
#include "sweep_backend.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include "json_file.hpp"
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

namespace medax {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

struct Running {
  std::size_t job;
  pid_t pid;
  Clock::time_point start;
  std::string timeout_error;  ///< set when the job is killed for its time: why
};

enum class Previous { none, done, changed };

/// `done`: the folder holds a successful run of this job with this configuration. `changed`: a
/// successful run of the same input and settings whose resolved configuration differs (the
/// pipeline file or a plugin default was edited since, or it predates config_hash).
Previous previous_run(const SweepJob& job, const fs::path& dir) {
  const nlohmann::json status = detail::read_json_file(dir / "status.json");
  if (!status.is_object() || status.value("status", "") != "ok" ||
      status.value("settings", std::vector<std::string>{}) != job.settings ||
      status.value("input", "") != job.input.string())
    return Previous::none;
  return status.value("config_hash", "") == job.config_hash ? Previous::done : Previous::changed;
}

/// How the sweep is being stopped after SIGINT/SIGTERM.
struct Stop {
  int signal = 0;  ///< 0: not stopping
  Clock::time_point deadline;
  bool killed = false;  ///< the grace ran out: SIGKILL sent
  sigset_t old_mask;
};

/// Starts `medax run FILE --job --quiet --input X --set ... --out DIR` with its own process
/// group (so a time-out kills all of it), stdout/stderr into the job folder, and the limits.
pid_t start_job(const SweepConfig& config, const SweepJob& job, const fs::path& dir, const SweepOptions& options) {
  std::vector<std::string> args{options.medax_executable.string(), "run", config.file.string(), "--job", "--quiet",
                                "--input", job.input.string(), "--out", dir.string()};
  for (const std::string& s : job.settings) {
    args.push_back("--set");
    args.push_back(s);
  }
  const std::string output = (dir / "output.txt").string();
  // Signals are held across fork: the child must not run the inherited handler (a forwarded
  // SIGTERM would only raise a flag that exec forgets); it resets them to the default first.
  sigset_t interrupts, old_mask;
  sigemptyset(&interrupts);
  sigaddset(&interrupts, SIGINT);
  sigaddset(&interrupts, SIGTERM);
  ::pthread_sigmask(SIG_BLOCK, &interrupts, &old_mask);
  const pid_t sweep_pid = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
    throw std::runtime_error("cannot start a job process (fork failed)");
  }
  if (pid == 0) {
    // A sweep killed outright (kill -9) cannot forward anything: its jobs die with it instead of
    // running on unrecorded, holding their folders against the resumed sweep.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != sweep_pid) std::_Exit(127);  // it died before prctl
    ::setpgid(0, 0);  // (the parent does it too: a signal forwarded at once must find the group)
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
    const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
      ::close(fd);
    }
    if (config.limits.memory_mib > 0) {
      const rlim_t bytes = static_cast<rlim_t>(config.limits.memory_mib * 1024.0 * 1024.0);
      const rlimit limit{bytes, bytes};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  ::setpgid(pid, pid);  // fails harmlessly once the child has exec'd (it did it itself)
  ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  return pid;
}

std::string tail_of(const fs::path& file, std::size_t lines) {
  std::ifstream in(file);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) all.push_back(line);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i)
    out += (out.empty() ? "" : " | ") + all[i];
  return out;
}

/// Why a job failed: the error its run recorded in run.json (the whole message, where the last
/// lines of its output may be only the tail of a multi-line one), else the output's last lines.
std::string job_error(const fs::path& dir) {
  const nlohmann::json run = detail::read_json_file(dir / "run.json");
  if (!run.is_object() || !run.contains("error") || !run["error"].is_string()) return tail_of(dir / "output.txt", 2);
  std::string error;
  std::istringstream lines(run["error"].get<std::string>());
  for (std::string line; std::getline(lines, line);)
    if (line.find_first_not_of(' ') != std::string::npos) error += (error.empty() ? "" : " | ") + line;
  return error;
}

/// Writes status.json; returns its `status`.
std::string record_status(const SweepJob& job, const fs::path& dir, int wait_status, const std::string& timeout_error,
                          double seconds, const SweepConfig& config, const Stop& stop) {
  nlohmann::json status;
  status["input"] = job.input.string();
  status["settings"] = job.settings;
  status["config_hash"] = job.config_hash;
  status["seconds"] = seconds;
  std::string state;
  const bool exited_ok = WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0;
  if (!timeout_error.empty()) {
    state = "timeout";
    status["error"] = timeout_error;
  } else if (stop.signal && !exited_ok) {
    state = "interrupted";
    status["signal"] = stop.signal;
    status["error"] = stop.killed && WIFSIGNALED(wait_status) && WTERMSIG(wait_status) == SIGKILL
                          ? fmt::format("the sweep was stopped by {}; the job was killed after the {} s grace",
                                        detail::signal_name(stop.signal), config.limits.interrupt_grace_seconds)
                          : fmt::format("the sweep was stopped by {}; the job stopped on it", detail::signal_name(stop.signal));
  } else if (WIFSIGNALED(wait_status)) {
    state = "crashed";
    status["signal"] = WTERMSIG(wait_status);
    status["error"] = fmt::format("killed by signal {} ({}); {}", WTERMSIG(wait_status), strsignal(WTERMSIG(wait_status)),
                                  tail_of(dir / "output.txt", 2));
  } else {
    const int code = WEXITSTATUS(wait_status);
    status["exit_code"] = code;
    state = code == 0 ? "ok" : "failed";
    if (code != 0) {
      std::string error = job_error(dir);
      // An allocation refused under the memory limit surfaces as bad_alloc.
      if (config.limits.memory_mib > 0 && error.find("bad_alloc") != std::string::npos)
        state = "memory", error = fmt::format("over the {} MiB memory limit: {}", config.limits.memory_mib, error);
      status["error"] = error;
    }
  }
  status["status"] = state;
  detail::write_json_file(dir / "status.json", status);
  return state;
}

std::string duration_text(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  return s >= 3600 ? fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60) : fmt::format("{}m{:02}s", s / 60, s % 60);
}

/// On the first SIGINT/SIGTERM: holds further ones, forwards it to every running job and sets
/// the grace deadline. In a Slurm task, a SIGTERM at the task's time limit is Slurm ending it:
/// the jobs are killed at once (Slurm's SIGKILL follows within KillWait) and recorded as time-outs.
void begin_stop(Stop& stop, std::vector<Running>& running, const SweepConfig& config, const SweepOptions& options,
                const std::optional<detail::TaskLimit>& task_limit) {
  stop.signal = detail::interrupt_signal();
  // A second Ctrl-C would _Exit in the handler and orphan the jobs: hold it until they are
  // recorded (the wait is bounded by the grace).
  sigset_t block;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  ::pthread_sigmask(SIG_BLOCK, &block, &stop.old_mask);
  if (task_limit && stop.signal == SIGTERM && Clock::now() >= task_limit->end - detail::TaskLimit::kSlack) {
    for (Running& r : running) {
      ::kill(-r.pid, SIGKILL);
      r.timeout_error = fmt::format("killed by Slurm at the task's time limit ({})", task_limit->text);
    }
    stop.killed = true;
    return;
  }
  stop.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(config.limits.interrupt_grace_seconds));
  for (const Running& r : running) ::kill(-r.pid, stop.signal);
  if (!options.quiet)
    fmt::print(stderr, "[sweep] {}: stopping {} running job{} (killed if still running after {} s)\n",
               detail::signal_name(stop.signal), running.size(), running.size() == 1 ? "" : "s",
               config.limits.interrupt_grace_seconds);
}

/// Drops the signals held while stopping (they would _Exit now), then restores the mask.
void end_stop(const Stop& stop) {
  if (!stop.signal) return;
  sigset_t held;
  sigemptyset(&held);
  sigaddset(&held, SIGINT);
  sigaddset(&held, SIGTERM);
  const timespec zero{0, 0};
  while (::sigtimedwait(&held, nullptr, &zero) > 0) {
  }
  ::pthread_sigmask(SIG_SETMASK, &stop.old_mask, nullptr);
}

/// Runs the `pending` jobs, `options.parallel_jobs` at a time, each recorded in its status.json;
/// counts them into `summary`. Returns how the sweep was stopped (signal 0: it was not).
Stop run_jobs(const SweepConfig& config, const std::vector<SweepJob>& jobs, const std::vector<std::size_t>& pending,
              const SweepOptions& options, SweepSummary& summary, const std::optional<detail::TaskLimit>& task_limit) {
  const fs::path jobs_dir = options.out_dir / "jobs";
  std::vector<Running> running;
  std::size_t next = 0, finished = 0;
  Stop stop;
  const auto sweep_start = Clock::now();
  const int parallel = std::max(1, options.parallel_jobs);
  while ((!stop.signal && next < pending.size()) || !running.empty()) {
    while (!detail::interrupt_requested() && next < pending.size() && static_cast<int>(running.size()) < parallel) {
      const SweepJob& job = jobs[pending[next]];
      const fs::path dir = jobs_dir / job.name;
      fs::create_directories(dir);
      fs::remove(dir / "status.json");
      running.push_back({pending[next], start_job(config, job, dir, options), Clock::now()});
      ++next;
    }
    if (detail::interrupt_requested() && !stop.signal) begin_stop(stop, running, config, options, task_limit);
    if (stop.signal && !stop.killed && Clock::now() >= stop.deadline) {
      for (const Running& r : running) ::kill(-r.pid, SIGKILL);
      stop.killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (auto it = running.begin(); it != running.end();) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - it->start).count();
      if (config.limits.timeout_seconds > 0 && elapsed > config.limits.timeout_seconds && it->timeout_error.empty() &&
          !stop.signal) {
        ::kill(-it->pid, SIGKILL);
        it->timeout_error = fmt::format("killed after the {} s time limit", config.limits.timeout_seconds);
      }
      int wait_status = 0;
      if (::waitpid(it->pid, &wait_status, WNOHANG) != it->pid) {
        ++it;
        continue;
      }
      const SweepJob& job = jobs[it->job];
      const std::string state =
          record_status(job, jobs_dir / job.name, wait_status, it->timeout_error, elapsed, config, stop);
      const bool ok = state == "ok";
      if (state == "interrupted") ++summary.interrupted;
      else ok ? ++summary.succeeded : ++summary.failed;
      ++finished;
      if (!options.quiet) {
        const double spent = std::chrono::duration<double>(Clock::now() - sweep_start).count();
        const double left = spent / finished * (pending.size() - finished);
        fmt::print(stderr, "[sweep] {}/{} done, {} failed, ~{} left{}\n", finished + summary.skipped, summary.total,
                   summary.failed, duration_text(left), ok ? "" : " (" + job.name + " " + state + ")");
      }
      it = running.erase(it);
    }
  }
  return stop;
}

}  // namespace

namespace detail {

std::vector<std::size_t> jobs_to_run(const std::vector<SweepJob>& jobs, const fs::path& jobs_dir,
                                     SweepSummary& summary, bool quiet) {
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    switch (previous_run(jobs[i], jobs_dir / jobs[i].name)) {
      case Previous::done: ++summary.skipped; break;
      case Previous::changed: ++summary.rerun_changed; pending.push_back(i); break;
      case Previous::none: pending.push_back(i); break;
    }
  }
  if (!quiet && summary.skipped)
    fmt::print(stderr, "[sweep] {} of {} jobs already finished: skipped\n", summary.skipped, jobs.size());
  if (!quiet && summary.rerun_changed)
    fmt::print(stderr, "[sweep] {} finished job{} run again: the configuration changed since (pipeline file, "
               "settings or plugin defaults)\n", summary.rerun_changed, summary.rerun_changed == 1 ? "" : "s");
  return pending;
}

std::string run_job_as_task(const SweepConfig& config, const SweepJob& job, const SweepOptions& options,
                            const std::optional<TaskLimit>& task_limit) {
  fs::create_directories(options.out_dir / "jobs");
  install_interrupt_handler();
  SweepSummary summary;
  summary.total = 1;
  const Stop stop = run_jobs(config, {job}, {0}, options, summary, task_limit);
  end_stop(stop);
  const nlohmann::json status = read_json_file(options.out_dir / "jobs" / job.name / "status.json");
  return status.is_object() ? status.value("status", "unknown") : "unknown";
}

}  // namespace detail

SweepSummary run_sweep(const SweepConfig& config, const std::vector<SweepJob>& jobs, const SweepOptions& options) {
  SweepSummary summary;
  summary.total = jobs.size();
  fs::create_directories(options.out_dir / "jobs");
  // The handler `medax run` uses: it only raises a flag, which the loop polls.
  detail::install_interrupt_handler();
  const std::vector<std::size_t> pending = detail::jobs_to_run(jobs, options.out_dir / "jobs", summary, options.quiet);
  const Stop stop = run_jobs(config, jobs, pending, options, summary, std::nullopt);
  write_sweep_results(config, jobs, options.out_dir);
  end_stop(stop);
  summary.signal = stop.signal;
  return summary;
}

}  // namespace medax
