// The options of `medax run` beyond those it shares with `validate`.
#include "commands.hpp"

#include <CLI/CLI.hpp>

namespace medax::cli {

namespace {

/// --backend slurm's options (docs/cluster.md), in their own help group.
void add_slurm_options(CLI::App& run, RunArgs& args) {
  const std::string group = "Slurm (--backend slurm)";
  SlurmArgs& s = args.slurm;
  run.add_option("--partition", s.partition, "Partition (default: the cluster's)")->group(group);
  run.add_option("--time", s.time, "Time limit per job, Slurm's format (default: `limits: timeout` + 1 min)")->group(group);
  run.add_option("--mem", s.memory, "Memory per job, e.g. 4G (default: `limits: memory_mib`)")->group(group);
  run.add_option("--cpus", s.cpus, "CPUs per job (--cpus-per-task)")->check(CLI::PositiveNumber)->group(group);
  run.add_option("--max-parallel", s.max_parallel, "Array tasks running at once (the array's %K)")
      ->check(CLI::PositiveNumber)->group(group);
  run.add_flag("--no-wait", s.no_wait, "Submit and return; `--results-only` collects later")->group(group);
  run.add_option("--retry", s.retries, "Resubmit jobs Slurm killed at its time/memory limit, with twice it, up to N times")
      ->check(CLI::NonNegativeNumber)->group(group);
  run.add_option("--poll", s.poll_seconds, "Seconds between squeue polls while waiting")
      ->check(CLI::PositiveNumber)->group(group);
  run.add_option("--slurm-task", args.slurm_task, "Run one task of a sweep's Slurm array (used by the batch script)")
      ->group("");
}

}  // namespace

void add_run_options(CLI::App& run, RunArgs& args) {
  run.add_option("--out,-o", args.out, "Run folder (default: medax-runs/<pipeline>-<input>)");
  run.add_flag("--quiet,-q", args.quiet, "Only errors on the terminal (log.txt has everything)");
  run.add_option("--jobs,-j", args.parallel_jobs, "Sweeps: jobs run in parallel, each in its own process")
      ->check(CLI::PositiveNumber);
  run.add_option("--timeout", args.timeout, "Sweeps: seconds per job before it is killed (overrides `limits:`)");
  run.add_option("--memory-mib", args.memory_mib, "Sweeps: address-space limit per job (overrides `limits:`)");
  run.add_flag("--results-only", args.results_only,
               "Sweeps: rewrite results.csv/md and plots from the job folders (after editing `table:` or `plots:`)");
  run.add_option("--backend", args.backend, "Sweeps: where the jobs run: local (this machine) or slurm (a job array)")
      ->check(CLI::IsMember({"local", "slurm"}));
  add_slurm_options(run, args);
  run.add_flag("--job", args.single_job, "Run as one job of a sweep (used by the sweep runner)")->group("");
}

}  // namespace medax::cli
