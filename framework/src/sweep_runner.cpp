// Runs sweep jobs, each in its own `medax run --job` process, a few at a time, with per-job
// time and memory limits. A job's status.json records how it ended; a finished job is skipped
// when the sweep runs again.
#include <medax/io.hpp>
#include <medax/kernel/sweep.hpp>

#include <fcntl.h>
#include <fmt/format.h>
#include "json_file.hpp"
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

namespace medax {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

struct Running {
  std::size_t job;
  pid_t pid;
  Clock::time_point start;
  bool timed_out = false;
};

bool already_done(const SweepJob& job, const fs::path& dir) {
  const nlohmann::json status = detail::read_json_file(dir / "status.json");
  return status.is_object() && status.value("status", "") == "ok" &&
         status.value("settings", std::vector<std::string>{}) == job.settings &&
         status.value("input", "") == job.input.string();
}

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
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start a job process (fork failed)");
  if (pid == 0) {
    ::setpgid(0, 0);
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

void record_status(const SweepJob& job, const fs::path& dir, int wait_status, bool timed_out, double seconds,
                   const SweepConfig& config) {
  nlohmann::json status;
  status["input"] = job.input.string();
  status["settings"] = job.settings;
  status["seconds"] = seconds;
  std::string state;
  if (timed_out) {
    state = "timeout";
    status["error"] = fmt::format("killed after the {} s time limit", config.limits.timeout_seconds);
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
      std::string error = tail_of(dir / "output.txt", 2);
      // An allocation refused under the memory limit surfaces as bad_alloc.
      if (config.limits.memory_mib > 0 && error.find("bad_alloc") != std::string::npos)
        state = "memory", error = fmt::format("over the {} MiB memory limit: {}", config.limits.memory_mib, error);
      status["error"] = error;
    }
  }
  status["status"] = state;
  detail::write_json_file(dir / "status.json", status);
}

std::string duration_text(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  return s >= 3600 ? fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60) : fmt::format("{}m{:02}s", s / 60, s % 60);
}

}  // namespace

SweepSummary run_sweep(const SweepConfig& config, const std::vector<SweepJob>& jobs, const SweepOptions& options) {
  SweepSummary summary;
  summary.total = jobs.size();
  const fs::path jobs_dir = options.out_dir / "jobs";
  fs::create_directories(jobs_dir);

  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (already_done(jobs[i], jobs_dir / jobs[i].name)) ++summary.skipped;
    else pending.push_back(i);
  }
  if (!options.quiet && summary.skipped)
    fmt::print(stderr, "[sweep] {} of {} jobs already finished: skipped\n", summary.skipped, jobs.size());

  std::vector<Running> running;
  std::size_t next = 0, finished = 0;
  const auto sweep_start = Clock::now();
  const int parallel = std::max(1, options.parallel_jobs);
  while (next < pending.size() || !running.empty()) {
    while (next < pending.size() && static_cast<int>(running.size()) < parallel) {
      const SweepJob& job = jobs[pending[next]];
      const fs::path dir = jobs_dir / job.name;
      fs::create_directories(dir);
      fs::remove(dir / "status.json");
      running.push_back({pending[next], start_job(config, job, dir, options), Clock::now()});
      ++next;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (auto it = running.begin(); it != running.end();) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - it->start).count();
      if (config.limits.timeout_seconds > 0 && elapsed > config.limits.timeout_seconds && !it->timed_out) {
        ::kill(-it->pid, SIGKILL);
        it->timed_out = true;
      }
      int wait_status = 0;
      if (::waitpid(it->pid, &wait_status, WNOHANG) != it->pid) {
        ++it;
        continue;
      }
      const SweepJob& job = jobs[it->job];
      record_status(job, jobs_dir / job.name, wait_status, it->timed_out, elapsed, config);
      const bool ok = !it->timed_out && WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0;
      ok ? ++summary.succeeded : ++summary.failed;
      ++finished;
      if (!options.quiet) {
        const double spent = std::chrono::duration<double>(Clock::now() - sweep_start).count();
        const double left = spent / finished * (pending.size() - finished);
        fmt::print(stderr, "[sweep] {}/{} done, {} failed, ~{} left{}\n", finished + summary.skipped, jobs.size(),
                   summary.failed, duration_text(left), ok ? "" : " (" + job.name + " failed)");
      }
      it = running.erase(it);
    }
  }
  write_sweep_results(config, jobs, options.out_dir);
  return summary;
}

}  // namespace medax
