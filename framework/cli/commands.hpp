#pragma once
// The `medax` sub-commands. Each returns the process exit code:
// 0 success, 1 a stage or the run failed, 2 bad usage or an invalid pipeline, 128 + the signal
// (130 SIGINT, 143 SIGTERM) when a run was interrupted (docs/pipeline-format.md).
#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}
namespace medax {
struct PipelineConfig;
struct SweepConfig;
}  // namespace medax

namespace medax::cli {

/// The exit code of a failed run: 128 + the signal when the user interrupted it, else 1.
inline int failed_run_exit_code(int signal) { return signal ? 128 + signal : 1; }

/// False (after printing why) when PIPELINE is missing or a folder; exit 2 then.
bool check_pipeline_file(const std::filesystem::path& pipeline);

/// `run --backend slurm` options (docs/cluster.md).
struct SlurmArgs {
  std::string partition, time, memory;
  int cpus = 0;
  int max_parallel = 0;
  bool no_wait = false;
  int retries = 0;
  double poll_seconds = 2;
};

struct RunArgs {
  std::filesystem::path pipeline;
  std::filesystem::path input;
  std::filesystem::path out;
  std::vector<std::string> settings;
  bool quiet = false;
  bool single_job = false;    ///< --job: run one job of a sweep (set by the sweep runner)
  bool results_only = false;  ///< --results-only: rewrite a sweep's table and plots, run nothing
  int parallel_jobs = 1;      ///< -j for sweeps
  double timeout = -1;        ///< per-job seconds for sweeps; < 0: from the file
  double memory_mib = -1;     ///< per-job MiB for sweeps; < 0: from the file
  std::string backend = "local";  ///< --backend: where a sweep's jobs run (local, slurm)
  SlurmArgs slurm;                ///< --backend slurm's options
  std::filesystem::path slurm_task;  ///< --slurm-task TASKS: run as one task of a sweep's Slurm array
};

/// Where `run` writes without --out: medax-runs/<pipeline>-<input stem> for a pipeline,
/// medax-runs/<name> for an experiment.
std::filesystem::path default_run_folder(const PipelineConfig& config);
std::filesystem::path default_run_folder(const SweepConfig& config);

/// Registers `run`'s own options (run_options.cpp) into `args`.
void add_run_options(CLI::App& run, RunArgs& args);

struct BenchArgs {
  std::filesystem::path pipeline;
  std::filesystem::path input;
  std::vector<std::string> settings;
  int warmup = 1;
  int repeat = 5;
};

int list_plugins();
/// Prints a stage's parameters; with `markdown`, the block its docs page embeds.
int describe(const std::string& name, bool markdown);
int validate(const RunArgs& args);
int run(const RunArgs& args);
/// `run` and `validate` on a pipeline with `sweep:` or `inputs:` (an experiment).
int run_sweep(const RunArgs& args);
int validate_sweep(const RunArgs& args);
int bench(const BenchArgs& args);

}  // namespace medax::cli
