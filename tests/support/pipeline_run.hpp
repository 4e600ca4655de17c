#pragma once
// Running a pipeline from a test: validate it against a registry and run it quietly.
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/runner.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace medax::test {

/// Loads `pipeline` against `registry` and runs it, without terminal output, into `out_dir`.
inline RunResult run_quietly(const std::filesystem::path& pipeline, const Registry& registry,
                             const std::filesystem::path& out_dir, const Overrides& overrides = {}) {
  const PipelineConfig config = load_pipeline(pipeline, registry, overrides);
  RunOptions options;
  options.out_dir = out_dir;
  options.quiet = true;
  return run_pipeline(config, options);
}

/// Writes `yaml` to `dir`/pipeline.yaml (relative paths in it are relative to `dir`) and runs it
/// into `dir`/`out`.
inline RunResult run_yaml_text(const std::filesystem::path& dir, const std::string& yaml, const Registry& registry,
                               const std::string& out = "run") {
  std::ofstream(dir / "pipeline.yaml") << yaml;
  return run_quietly(dir / "pipeline.yaml", registry, dir / out);
}

}  // namespace medax::test
