#pragma once
// Running a pipeline written as YAML text into a scratch run folder, and reading its JSON.
#include "kernel_test_support.hpp"

#include <medax/kernel/runner.hpp>

#include <nlohmann/json.hpp>

namespace medax::test {

struct Run {
  PipelineConfig config;
  RunResult result;
  std::filesystem::path dir;  ///< the run folder
};

/// Writes `yaml` to `root`/pipeline.yaml, validates it against the good registry and runs it
/// into `root`/run.
inline Run run_yaml(const std::filesystem::path& root, const std::string& yaml, const Overrides& overrides = {}) {
  Run run;
  run.config = load_pipeline(write_text(root / "pipeline.yaml", yaml), good_registry(), overrides);
  run.dir = root / "run";
  RunOptions options;
  options.out_dir = run.dir;
  options.quiet = true;
  run.result = run_pipeline(run.config, options);
  return run;
}

inline nlohmann::json read_json(const std::filesystem::path& path) { return nlohmann::json::parse(read_text(path)); }

}  // namespace medax::test
