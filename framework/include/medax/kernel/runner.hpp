#pragma once
// Runs a validated pipeline into a run folder.
#include <medax/kernel/pipeline.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace medax {

struct RunOptions {
  std::filesystem::path out_dir;  ///< created if missing
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
  std::filesystem::path out_dir;
  std::vector<StageTiming> timings;  ///< one per stage that ran
};

/// Runs every stage in order, writing config.resolved.yaml, log.txt, metrics.json,
/// timings.json and the configured outputs. A stage that throws stops the run; the outputs of
/// the stages completed before it are still written.
RunResult run_pipeline(const PipelineConfig& config, const RunOptions& options);

}  // namespace medax
