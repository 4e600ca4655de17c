#pragma once
// Experiments: a pipeline with `inputs:` (a list, globs or a manifest) and/or `sweep:` (values
// per STAGE.PARAM or STAGE.plugin) expands into jobs, the cartesian product. Every job runs in
// its own `medax run` process, so a crash, a time-out or a memory blow-up fails only that job.
#include <medax/kernel/pipeline.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace medax {

/// One swept dimension. A plain axis sets one key (`STAGE.PARAM` or `STAGE.plugin`) to each
/// value; a named axis (a key without a dot) takes bundles of settings applied together, e.g.
/// `method: [{name: durix, prep.plugin: delaunay_surface, extract.plugin: durix}, ...]`.
struct SweepAxis {
  std::string key;                                ///< results column
  std::vector<std::string> values;                ///< what the column shows for each choice
  std::vector<std::vector<std::string>> settings; ///< "KEY=VALUE" settings of each choice
};

struct PlotSpec {
  std::string x, y;        ///< results.csv column names
  std::string series;      ///< column whose values make one curve each (default: input)
  bool log_x = false, log_y = false;
  bool points_only = false;  ///< `style: points`: a scatter (e.g. across meshes), no lines
};

struct SweepLimits {
  double timeout_seconds = 0;  ///< 0: none
  double memory_mib = 0;       ///< address-space limit per job; 0: none
  /// After Ctrl-C/SIGTERM the running jobs get the signal and this long to stop, then SIGKILL.
  double interrupt_grace_seconds = 10;
};

/// Variables of one input, from its manifest line (`armadillo.off spheres=83 note=x`): a sweep
/// value `${spheres}` becomes that input's value in its jobs (e.g. a method's sphere count per
/// model); `${spheres:-100}` gives 100 to an input that does not set it.
struct InputVariables {
  std::map<std::string, std::string> values;
  std::string origin;  ///< "MANIFEST:LINE" where they were given
};

struct SweepConfig {
  std::filesystem::path file;
  std::string name;
  std::vector<std::filesystem::path> inputs;  ///< absolute, in order
  /// Per-input variables by absolute input path (only inputs from manifest lines that set some).
  std::map<std::filesystem::path, InputVariables> variables;
  std::vector<SweepAxis> axes;
  std::vector<PlotSpec> plots;
  /// Columns of results.md (`table:`); empty: every column. results.csv always has them all.
  std::vector<std::string> table_columns;
  SweepLimits limits;
};

struct SweepJob {
  std::string name;  ///< folder name under jobs/, unique and readable
  std::filesystem::path input;
  std::vector<std::pair<std::string, std::string>> assignment;  ///< axis key -> shown value
  std::vector<std::string> settings;                            ///< "KEY=VALUE" for --set
  std::size_t from_command_line = 0;  ///< the first this many settings are the command line's --set
  /// Hash of the job's resolved configuration (the pipeline with its input and settings, every
  /// default filled in); validate_sweep sets it. A finished job with another hash runs again.
  std::string config_hash;
};

/// True when the file has `sweep:` or `inputs:` (so `medax run` runs it as an experiment).
bool is_sweep(const std::filesystem::path& pipeline);
/// Reads the sweep parts of a pipeline file. Throws PipelineError with positions.
SweepConfig load_sweep(const std::filesystem::path& pipeline);
/// The cartesian product, inputs outermost, then the axes in file order; `${NAME}` in a setting's
/// value is replaced by the job input's variable NAME. Throws PipelineError when an input lacks a
/// variable a value uses (load_sweep checks the file's own inputs; this catches a replaced input).
std::vector<SweepJob> expand_sweep(const SweepConfig& config);
/// Validates every job as a single pipeline before any work and sets each job's config_hash.
/// Throws PipelineError.
void validate_sweep(const SweepConfig& config, std::vector<SweepJob>& jobs, const Registry& registry);

struct SweepOptions {
  std::filesystem::path out_dir;
  std::filesystem::path medax_executable;  ///< the `medax` binary that runs each job
  int parallel_jobs = 1;
  bool quiet = false;
};

struct SweepSummary {
  std::size_t total = 0, skipped = 0, succeeded = 0, failed = 0;
  std::size_t rerun_changed = 0;  ///< finished jobs run again because their configuration changed
  std::size_t interrupted = 0;    ///< jobs stopped by a Ctrl-C/SIGTERM of the sweep
  int signal = 0;                 ///< SIGINT/SIGTERM that stopped the sweep; 0 if none
};

/// Runs the jobs not already finished (a job folder whose status.json says ok for the same
/// input, settings and config_hash is skipped: a sweep can be resumed), then writes results.csv,
/// results.md and plots. On SIGINT/SIGTERM (the handler of run_context.hpp) it starts no more
/// jobs, forwards the signal to every running job's process group, waits up to
/// limits.interrupt_grace_seconds and then kills them, records them as `interrupted`, writes the
/// results of what finished and returns with `signal` set.
SweepSummary run_sweep(const SweepConfig& config, const std::vector<SweepJob>& jobs, const SweepOptions& options);

/// Collects every job's status, metrics and timings into results.csv and results.md, and draws
/// the plots (gnuplot: PNG and SVG). Returns the number of rows.
std::size_t write_sweep_results(const SweepConfig& config, const std::vector<SweepJob>& jobs,
                                const std::filesystem::path& out_dir);

}  // namespace medax
