#pragma once
// Internal: one stage entry of a pipeline checked against its plugin's declared parameters, and
// its configured instance created; the scalar parsers the pipeline file shares with it.
#include "diagnostics.hpp"

#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>

namespace medax::detail {

/// "an extraction stage", "a significance stage": the role with its article.
std::string a_stage(Role role);
std::optional<std::string> scalar(Diagnostics& check, const YAML::Node& node, const char* what);
std::optional<long long> parse_int(const std::string& s);
std::optional<bool> parse_bool(const std::string& s);

/// Validates stage entries, reporting every problem to the diagnostics.
class StageValidator {
 public:
  StageValidator(Diagnostics& check, const Registry& registry) : check_(check), registry_(registry) {}

  /// Validates a stage entry (map with plugin/id/params, or a bare plugin name for nested
  /// stages) and creates its configured instance. Returns nullopt when invalid.
  std::optional<StageConfig> stage(const YAML::Node& node, std::optional<Role> required_role);

 private:
  /// The registered plugin a stage names, of the required role; nullptr (reported) otherwise.
  const RegisteredStage* plugin_of(const YAML::Node& node, const YAML::Node& plugin_node,
                                   std::optional<Role> required_role);
  /// True when `params:` is absent, or a map whose every key the plugin declares.
  bool params_declared(const YAML::Node& params_node, const StageInfo& info);
  /// Every declared parameter: its given value, parsed, or its default.
  bool bind_params(const YAML::Node& node, const YAML::Node& params_node, const StageInfo& info, ParamSet& params);
  /// Creates and configures the stage; its own parameter check's complaint is reported.
  std::optional<StageConfig> instantiate(const RegisteredStage& registered, const YAML::Node& plugin_node,
                                         const YAML::Node& params_node, StageConfig config);
  /// A parameter left out: its default (a stage parameter: its default stage, validated).
  std::optional<ParamValue> default_of(const ParamSpec& spec, const YAML::Node& owner);
  /// A validated nested stage as the value of a stage parameter.
  static ParamValue make_ref(StageConfig nested);
  /// A given parameter value, checked against its type and range.
  std::optional<ParamValue> parse(const ParamSpec& spec, const YAML::Node& node, const std::string& plugin);

  Diagnostics& check_;
  const Registry& registry_;
};

}  // namespace medax::detail
