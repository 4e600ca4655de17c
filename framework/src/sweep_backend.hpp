#pragma once
// Sweep backends beyond the local one: the Slurm backend (slurm_backend.cpp) submits the jobs as
// one job array whose tasks run each job exactly as the local runner does (sweep_runner.cpp).
// Internal to libmedax and its CLI.
#include <medax/kernel/sweep.hpp>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace medax {

/// `medax run --backend slurm` options (docs/cluster.md).
struct SlurmOptions {
  std::string partition;  ///< --partition; empty: the cluster's default
  std::string time;       ///< --time in Slurm's format; empty: from `limits: timeout`, else the partition's
  std::string memory;     ///< --mem (e.g. 4G); empty: from `limits: memory_mib`, else the partition's
  int cpus = 0;           ///< --cpus-per-task; 0: Slurm's default
  int max_parallel = 0;   ///< the array's `%K`: tasks running at once; 0: no limit
  bool wait = true;       ///< false (--no-wait): submit and return
  int retries = 0;        ///< re-submissions of jobs Slurm killed at its time or memory limit, with twice it
  double poll_seconds = 2;
  /// `medax run` arguments that rebuild the same experiment in a task (pipeline, --input, --set...).
  std::vector<std::string> task_args;
};

/// Submits the jobs not finished yet as one Slurm job array (or waits for the array an earlier
/// `--no-wait` submitted, then submits what is still missing), waits for it with progress lines
/// unless `slurm.wait` is false, records the tasks Slurm killed, and writes the results.
/// Throws std::runtime_error (what to do included) when sbatch is missing or refuses.
SweepSummary run_sweep_on_slurm(const SweepConfig& config, const std::vector<SweepJob>& jobs,
                                const SweepOptions& options, const SlurmOptions& slurm);

/// `--results-only` after a `--no-wait` submission: records the tasks of a finished array that
/// Slurm killed before they could, then writes the results. Returns the rows; `note` says when
/// the array is still running (the table then shows its unfinished jobs as not run).
std::size_t collect_slurm_results(const SweepConfig& config, const std::vector<SweepJob>& jobs,
                                  const std::filesystem::path& out_dir, std::string& note);

/// One array task (`medax run ... --slurm-task TASKS`): runs the job named on line
/// $SLURM_ARRAY_TASK_ID of TASKS as the local runner does. Returns the exit code.
int run_slurm_task(const SweepConfig& config, std::vector<SweepJob> jobs, const SweepOptions& options,
                   const std::filesystem::path& tasks_file);

namespace detail {

/// When Slurm's time limit of this task ends. A SIGTERM within kSlack of it is Slurm's time-out.
struct TaskLimit {
  static constexpr std::chrono::seconds kSlack{15};
  std::chrono::steady_clock::time_point end;
  std::string text;  ///< the limit as Slurm shows it, e.g. 1:00:00
};

/// The indices of the jobs to run: all but those whose folder holds a successful run of the same
/// configuration (counted into `summary.skipped`; finished runs of another configuration into
/// `summary.rerun_changed`). Prints both counts unless `quiet`.
std::vector<std::size_t> jobs_to_run(const std::vector<SweepJob>& jobs, const std::filesystem::path& jobs_dir,
                                     SweepSummary& summary, bool quiet);

/// Runs one job as the local runner does (its own process, the limits, status.json); with
/// `task_limit`, Slurm's SIGTERM at that limit records it as a time-out. Returns its status.
std::string run_job_as_task(const SweepConfig& config, const SweepJob& job, const SweepOptions& options,
                            const std::optional<TaskLimit>& task_limit);

}  // namespace detail
}  // namespace medax
