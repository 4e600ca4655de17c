// `medax run` on an experiment: expand, validate every job, run them in parallel processes (or
// as a Slurm job array: --backend slurm), write the results table and plots.
#include "commands.hpp"

#include "sweep_backend.hpp"

#include <medax/kernel/registry.hpp>
#include <medax/kernel/sweep.hpp>

#include <boost/dll/runtime_symbol_info.hpp>
#include <fmt/format.h>

#include <csignal>
#include <optional>

namespace medax::cli {

namespace {

struct Experiment {
  SweepConfig config;
  std::vector<SweepJob> jobs;
};

/// Reads, expands and (unless `validate` is false) validates every job; prints the diagnostics
/// and returns nullopt on error.
std::optional<Experiment> load_experiment(const RunArgs& args, const Registry& registry, bool validate = true) {
  SweepConfig config;
  std::vector<SweepJob> jobs;
  try {
    config = load_sweep(args.pipeline);
    if (!args.input.empty()) config.inputs = {std::filesystem::absolute(args.input).lexically_normal()};
    if (args.timeout >= 0) config.limits.timeout_seconds = args.timeout;
    if (args.memory_mib >= 0) config.limits.memory_mib = args.memory_mib;
    jobs = expand_sweep(config);
    for (SweepJob& job : jobs) {  // --set applies to every job, before the swept values
      job.settings.insert(job.settings.begin(), args.settings.begin(), args.settings.end());
      job.from_command_line = args.settings.size();
    }
    if (validate) validate_sweep(config, jobs, registry);
  } catch (const PipelineError& e) {
    for (const Diagnostic& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.format());
    return std::nullopt;
  }
  return Experiment{std::move(config), std::move(jobs)};
}

/// The `medax run` arguments that make a Slurm task rebuild this experiment and its jobs.
std::vector<std::string> task_arguments(const RunArgs& args) {
  std::vector<std::string> out{"run", std::filesystem::absolute(args.pipeline).lexically_normal().string()};
  if (!args.input.empty()) out.insert(out.end(), {"--input", std::filesystem::absolute(args.input).string()});
  for (const std::string& s : args.settings) out.insert(out.end(), {"--set", s});
  if (args.timeout >= 0) out.insert(out.end(), {"--timeout", fmt::format("{}", args.timeout)});
  if (args.memory_mib >= 0) out.insert(out.end(), {"--memory-mib", fmt::format("{}", args.memory_mib)});
  return out;
}

SlurmOptions slurm_options(const RunArgs& args) {
  SlurmOptions s;
  s.partition = args.slurm.partition;
  s.time = args.slurm.time;
  s.memory = args.slurm.memory;
  s.cpus = args.slurm.cpus;
  s.max_parallel = args.slurm.max_parallel;
  s.wait = !args.slurm.no_wait;
  s.retries = args.slurm.retries;
  s.poll_seconds = args.slurm.poll_seconds;
  s.task_args = task_arguments(args);
  return s;
}

SweepOptions sweep_options(const RunArgs& args, const SweepConfig& config) {
  SweepOptions options;
  options.out_dir = args.out.empty() ? default_run_folder(config) : args.out;
  options.medax_executable = boost::dll::program_location().string();
  options.parallel_jobs = args.parallel_jobs;
  options.quiet = args.quiet;
  return options;
}

/// `--slurm-task`: this process is one task of the array; it runs its job alone.
int run_task(const RunArgs& args) {
  auto experiment = load_experiment(args, Registry::global(), false);  // the task validates its own job
  if (!experiment) return 2;
  SweepOptions options = sweep_options(args, experiment->config);
  options.parallel_jobs = 1;
  return run_slurm_task(experiment->config, std::move(experiment->jobs), options, args.slurm_task);
}

int write_results_only(const Experiment& experiment, const SweepOptions& options) {
  std::string note;
  const std::size_t rows = collect_slurm_results(experiment.config, experiment.jobs, options.out_dir, note);
  if (!note.empty()) fmt::print(stderr, "note: {}\n", note);
  fmt::print("results: {} ({} rows)\n",
             std::filesystem::absolute(options.out_dir / "results.csv").lexically_normal().string(), rows);
  return 0;
}

}  // namespace

int validate_sweep(const RunArgs& args) {
  const auto experiment = load_experiment(args, Registry::global());
  if (!experiment) return 2;
  fmt::print("{}: valid experiment ({} jobs: {} inputs x {} combinations)\n", args.pipeline.string(),
             experiment->jobs.size(), experiment->config.inputs.size(),
             experiment->jobs.size() / std::max<std::size_t>(1, experiment->config.inputs.size()));
  return 0;
}

int run_sweep(const RunArgs& args) {
  if (!args.slurm_task.empty()) return run_task(args);
  auto experiment = load_experiment(args, Registry::global());
  if (!experiment) return 2;
  const SweepConfig& config = experiment->config;
  const std::vector<SweepJob>& jobs = experiment->jobs;  // each with its config_hash
  const SweepOptions options = sweep_options(args, config);
  if (args.results_only) return write_results_only(*experiment, options);
  const bool slurm = args.backend == "slurm";
  if (!args.quiet)
    fmt::print(stderr, "[sweep] {} jobs ({} inputs x {} combinations), {}, into {}\n", jobs.size(),
               config.inputs.size(), config.inputs.empty() ? 0 : jobs.size() / config.inputs.size(),
               slurm ? std::string("as a Slurm job array") : fmt::format("{} at a time", options.parallel_jobs),
               options.out_dir.string());
  const SweepSummary summary =
      slurm ? run_sweep_on_slurm(config, jobs, options, slurm_options(args)) : run_sweep(config, jobs, options);
  if (slurm && summary.signal) return failed_run_exit_code(summary.signal);  // it said what keeps running
  if (slurm && args.slurm.no_wait) {
    fmt::print("--no-wait: once the array has run (`squeue` shows it), the same command with --results-only "
               "collects the results\n");
    return 0;
  }
  fmt::print("results: {} ({} ok, {} failed, {} skipped as already done{}{})\n",
             std::filesystem::absolute(options.out_dir / "results.csv").lexically_normal().string(),
             summary.succeeded, summary.failed, summary.skipped,
             summary.rerun_changed ? fmt::format(", {} run again as their configuration changed", summary.rerun_changed)
                                   : "",
             summary.signal ? fmt::format(", {} interrupted", summary.interrupted) : "");
  if (summary.signal) {
    fmt::print(stderr, "interrupted by {}: {} job(s) stopped, {} not started; run the same command again to "
               "resume (interrupted and unstarted jobs run, finished ones are skipped)\n",
               summary.signal == SIGINT ? "SIGINT (Ctrl-C)" : summary.signal == SIGTERM ? "SIGTERM" : "a signal",
               summary.interrupted,
               summary.total - summary.skipped - summary.succeeded - summary.failed - summary.interrupted);
    return failed_run_exit_code(summary.signal);
  }
  return summary.failed == 0 ? 0 : 1;
}

}  // namespace medax::cli
