// `medax run` on an experiment: expand, validate every job, run them in parallel processes,
// write the results table and plots.
#include "commands.hpp"

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

/// Reads, expands and validates every job; prints the diagnostics and returns nullopt on error.
std::optional<Experiment> load_experiment(const RunArgs& args, const Registry& registry) {
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
    validate_sweep(config, jobs, registry);
  } catch (const PipelineError& e) {
    for (const Diagnostic& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.format());
    return std::nullopt;
  }
  return Experiment{std::move(config), std::move(jobs)};
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
  auto experiment = load_experiment(args, Registry::global());
  if (!experiment) return 2;
  const SweepConfig& config = experiment->config;
  const std::vector<SweepJob>& jobs = experiment->jobs;  // each with its config_hash
  SweepOptions options;
  options.out_dir = args.out.empty() ? std::filesystem::path("medax-runs") / config.name : args.out;
  options.medax_executable = boost::dll::program_location().string();
  options.parallel_jobs = args.parallel_jobs;
  options.quiet = args.quiet;
  if (args.results_only) {
    const std::size_t rows = write_sweep_results(config, jobs, options.out_dir);
    fmt::print("results: {} ({} rows)\n",
               std::filesystem::absolute(options.out_dir / "results.csv").lexically_normal().string(), rows);
    return 0;
  }
  if (!args.quiet)
    fmt::print(stderr, "[sweep] {} jobs ({} inputs x {} combinations), {} at a time, into {}\n", jobs.size(),
               config.inputs.size(), config.inputs.empty() ? 0 : jobs.size() / config.inputs.size(),
               options.parallel_jobs, options.out_dir.string());
  const SweepSummary summary = run_sweep(config, jobs, options);
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
