// Writing a validated pipeline back as YAML with every default filled in, and formatting
// diagnostics.
#include <medax/kernel/pipeline.hpp>
#include <medax/stage.hpp>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

namespace medax {

std::string Diagnostic::format() const {
  if (line > 0) return fmt::format("{}:{}:{}: error: {}", file, line, column, message);
  return fmt::format("{}: error: {}", file, message);
}

namespace {
std::string join_diagnostics(const std::vector<Diagnostic>& diagnostics) {
  std::string out;
  for (const Diagnostic& d : diagnostics) out += (out.empty() ? "" : "\n") + d.format();
  return out;
}

// Shortest text that reads back to the same double; infinities in YAML spelling.
std::string real_text(double v) {
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

void emit_params(YAML::Emitter& out, const ParamSet& params);

void emit_value(YAML::Emitter& out, const ParamValue& value) {
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) out << v;
        else if constexpr (std::is_same_v<T, long long>) out << v;
        else if constexpr (std::is_same_v<T, double>) out << real_text(v);
        else if constexpr (std::is_same_v<T, std::string>) out << YAML::DoubleQuoted << v;
        else {
          out << YAML::BeginMap << YAML::Key << "plugin" << YAML::Value << v->plugin;
          emit_params(out, v->params);
          out << YAML::EndMap;
        }
      },
      value);
}

void emit_params(YAML::Emitter& out, const ParamSet& params) {
  if (params.all().empty()) return;
  out << YAML::Key << "params" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, value] : params.all()) {
    out << YAML::Key << name << YAML::Value;
    emit_value(out, value);
  }
  out << YAML::EndMap;
}
}  // namespace

PipelineError::PipelineError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join_diagnostics(diagnostics)), diagnostics_(std::move(diagnostics)) {}

std::string resolved_yaml(const PipelineConfig& config) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "medax" << YAML::Value << 1;
  out << YAML::Key << "name" << YAML::Value << config.name;
  out << YAML::Key << "seed" << YAML::Value << config.seed;
  out << YAML::Key << "input" << YAML::Value << config.input.string();
  if (!config.medial_input.empty())
    out << YAML::Key << "medial_input" << YAML::Value << config.medial_input.string();
  out << YAML::Key << "stages" << YAML::Value << YAML::BeginSeq;
  for (const StageConfig& stage : config.stages) {
    out << YAML::BeginMap;
    out << YAML::Key << "plugin" << YAML::Value << stage.plugin;
    out << YAML::Key << "id" << YAML::Value << stage.id;
    emit_params(out, stage.params);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "outputs" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "medial" << YAML::Value << YAML::Flow << config.outputs.medial;
  out << YAML::Key << "surface" << YAML::Value << YAML::Flow << config.outputs.surface;
  out << YAML::Key << "frame" << YAML::Value << (config.outputs.input_frame ? "input" : "working");
  out << YAML::EndMap;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace medax
