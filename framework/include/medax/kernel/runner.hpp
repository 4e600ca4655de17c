#pragma once
// Runs a validated pipeline into a run folder.
#include <medax/kernel/pipeline.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace medax {

struct RunOptions {
  /// The run folder: missing, empty, or a previous run folder (replaced whole); any other
  /// non-empty folder is refused. The folder containing it must be writable.
  std::filesystem::path out_dir;
  bool quiet = false;             ///< no log lines on stderr
};

struct StageTiming {
  std::string id, plugin;
  double seconds = 0;
  double peak_memory_mib = 0;  ///< the stage's own peak resident memory
  bool ok = false;
};

struct RunResult {
  bool ok = false;
  std::string failed_stage;  ///< id of the stage that threw ("run folder" when none could start)
  std::string error;
  bool wrote_log = false;    ///< false when the run folder or its log could not be made
  int signal = 0;            ///< SIGINT or SIGTERM when the user stopped the run, else 0
  std::filesystem::path out_dir;  ///< the run folder; the staging folder if it could not be published
  std::vector<StageTiming> timings;  ///< one per stage that ran
};

/// Runs every stage in order, writing config.resolved.yaml, log.txt, metrics.json,
/// timings.json, the configured outputs and last run.json (status ok|failed|interrupted). A
/// stage that throws stops the run; the outputs of the stages completed before it are still
/// written. Everything goes into `<out_dir>.partial-<pid>`, renamed over out_dir when the run
/// ends (ok, failed or interrupted); staging folders of killed runs into out_dir are removed
/// and named in the log (docs/pipeline-format.md, "What a run folder guarantees").
RunResult run_pipeline(const PipelineConfig& config, const RunOptions& options);

}  // namespace medax
