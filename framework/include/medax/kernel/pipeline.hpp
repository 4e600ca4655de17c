#pragma once
// Pipelines as data: a YAML file read into a validated configuration. Every problem is found
// before any work starts and reported as file:line:column with what to do.
#include <medax/kernel/registry.hpp>
#include <medax/params.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace medax {

struct Diagnostic {
  std::string file;
  int line = 0;    ///< 1-based; 0 when not tied to a position
  int column = 0;  ///< 1-based
  std::string message;
  std::string format() const;  ///< "file:line:column: error: message"
};

/// All problems found in a pipeline; what() lists them one per line.
class PipelineError : public std::runtime_error {
 public:
  explicit PipelineError(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

struct StageConfig {
  std::string id;
  std::string plugin;
  Role role = Role::Extraction;
  ParamSet params;
  std::shared_ptr<Stage> instance;  ///< created and configured during validation
};

/// Which results to write: for each product, the formats (file extensions).
struct OutputConfig {
  std::vector<std::string> medial;   ///< of ma, ply, obj -> medial.<ext>
  std::vector<std::string> surface;  ///< of off, obj, ply, stl -> surface.<ext>
  bool input_frame = true;           ///< map outputs back to the input file's coordinates
};

struct PipelineConfig {
  std::filesystem::path file;  ///< the YAML it came from
  std::string name;            ///< `name:` or the file's stem
  std::uint64_t seed = 0;
  std::filesystem::path input;          ///< surface mesh (absolute)
  std::filesystem::path medial_input;   ///< optional .ma to start from (absolute)
  std::vector<StageConfig> stages;
  OutputConfig outputs;
};

/// Command-line changes applied before validation.
struct Overrides {
  std::filesystem::path input;       ///< replaces `input:` when not empty
  /// "STAGE.PARAM=VALUE" (STAGE being a stage id), or "STAGE.plugin=NAME" to swap the stage's
  /// plugin (its params are then reset to the new plugin's defaults).
  std::vector<std::string> settings;
  std::string origin = "--set";      ///< how diagnostics name a setting ("--set", "sweep")
  std::size_t from_command_line = 0; ///< the first this many settings are the command line's --set
};

/// Reads and validates a pipeline. Throws PipelineError with every problem found.
PipelineConfig load_pipeline(const std::filesystem::path& file, const Registry& registry,
                             const Overrides& overrides = {});

/// The configuration with every default filled in, as YAML that load_pipeline accepts and that
/// reproduces the run.
std::string resolved_yaml(const PipelineConfig& config);

}  // namespace medax
