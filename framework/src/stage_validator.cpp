#include "stage_validator.hpp"

#include "suggest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace medax::detail {

namespace {

const std::vector<std::string> kStageKeys{"plugin", "id", "params", "enabled"};

std::optional<double> parse_real(const std::string& s) {
  if (s == ".inf" || s == "inf" || s == "+.inf") return INFINITY;
  if (s == "-.inf" || s == "-inf") return -INFINITY;
  try {
    std::size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

}  // namespace

/// "an extraction stage", "a significance stage": the role with its article.
std::string a_stage(Role role) {
  const std::string_view name = to_string(role);
  const bool vowel = std::string_view("aeiou").find(name.front()) != std::string_view::npos;
  return fmt::format("{} {} stage", vowel ? "an" : "a", name);
}

std::optional<std::string> scalar(Diagnostics& check, const YAML::Node& node, const char* what) {
  if (!node.IsScalar()) {
    check.error(node, fmt::format("{} must be a single value", what));
    return std::nullopt;
  }
  return node.Scalar();
}

std::optional<long long> parse_int(const std::string& s) {
  try {
    std::size_t used = 0;
    const long long v = std::stoll(s, &used, 10);
    if (used == s.size()) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

std::optional<bool> parse_bool(const std::string& s) {
  if (s == "true" || s == "yes" || s == "on" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "no" || s == "off" || s == "False" || s == "FALSE") return false;
  return std::nullopt;
}

std::optional<StageConfig> StageValidator::stage(const YAML::Node& node, std::optional<Role> required_role) {
  if (!node.IsMap() && !(node.IsScalar() && required_role)) {
    check_.error(node, "a stage is a map with `plugin:` (and optional `id:`, `params:`)");
    return std::nullopt;
  }
  // Copy-constructed, not assigned: yaml-cpp throws when a missing key's node is assigned.
  const YAML::Node plugin_node = node.IsMap() ? node["plugin"] : node;
  const YAML::Node params_node = node.IsMap() ? node["params"] : YAML::Node();
  StageConfig config;
  if (node.IsMap()) {
    check_.unknown_keys(node, kStageKeys, "stage");
    if (node["id"])
      if (auto id = scalar(check_, node["id"], "`id`")) config.id = *id;
  }
  const RegisteredStage* registered = plugin_of(node, plugin_node, required_role);
  if (!registered) return std::nullopt;
  const StageInfo& info = registered->info();
  config.plugin = info.name;
  config.role = info.role;
  if (config.id.empty()) config.id = info.name;
  const bool names_ok = params_declared(params_node, info);
  if (!bind_params(node, params_node, info, config.params) || !names_ok) return std::nullopt;
  return instantiate(*registered, plugin_node, params_node, std::move(config));
}

const RegisteredStage* StageValidator::plugin_of(const YAML::Node& node, const YAML::Node& plugin_node,
                                 std::optional<Role> required_role) {
  if (!plugin_node) {
    check_.error(node, "this stage has no `plugin:`; add `plugin: NAME` (see `medax plugins`)");
    return nullptr;
  }
  const auto name = scalar(check_, plugin_node, "`plugin`");
  if (!name) return nullptr;
  const RegisteredStage* registered = registry_.find(*name);
  if (!registered) {
    check_.error(plugin_node, fmt::format("unknown plugin '{}'{}; `medax plugins` lists them", *name,
                                          did_you_mean(registry_.suggest(*name))));
    return nullptr;
  }
  const Role role = registered->info().role;
  if (required_role && role != *required_role) {
    check_.error(plugin_node, fmt::format("'{}' is {} but this parameter needs {}", *name, a_stage(role),
                                          a_stage(*required_role)));
    return nullptr;
  }
  return registered;
}

bool StageValidator::params_declared(const YAML::Node& params_node, const StageInfo& info) {
  if (!params_node || params_node.IsNull()) return true;
  if (!params_node.IsMap()) {
    check_.error(params_node, "`params:` must be a map of NAME: VALUE");
    return false;
  }
  std::vector<std::string> declared;
  for (const ParamSpec& spec : info.params) declared.push_back(spec.name);
  bool ok = true;
  for (const auto& kv : params_node) {
    const std::string key = kv.first.Scalar();
    if (std::find(declared.begin(), declared.end(), key) != declared.end()) continue;
    check_.error(kv.first, fmt::format("'{}' has no parameter '{}'{}; `medax describe {}` lists its parameters",
                                       info.name, key, did_you_mean(closest_names(key, declared)),
                                       info.name));
    ok = false;
  }
  return ok;
}

bool StageValidator::bind_params(const YAML::Node& node, const YAML::Node& params_node, const StageInfo& info, ParamSet& params) {
  bool ok = true;
  for (const ParamSpec& spec : info.params) {
    // An absent parameter is an undefined node (a default-constructed Node counts as given).
    const YAML::Node value = params_node && params_node.IsMap() ? params_node[spec.name]
                                                                : YAML::Node(YAML::NodeType::Undefined);
    std::optional<ParamValue> v = value ? parse(spec, value, info.name) : default_of(spec, node);
    if (v) params.set(spec.name, std::move(*v));
    else ok = false;
  }
  return ok;
}

std::optional<StageConfig> StageValidator::instantiate(const RegisteredStage& registered, const YAML::Node& plugin_node,
                                       const YAML::Node& params_node, StageConfig config) {
  config.instance = std::shared_ptr<Stage>(registered.entry.create());
  config.instance->set_id(config.id);
  config.instance->configure(config.params);
  try {
    config.instance->check_params();
  } catch (const std::exception& e) {
    check_.error(params_node && params_node.IsMap() ? params_node : plugin_node,
                 fmt::format("'{}': {}", config.plugin, e.what()));
    return std::nullopt;
  }
  return config;
}

std::optional<ParamValue> StageValidator::default_of(const ParamSpec& spec, const YAML::Node& owner) {
  if (spec.type != ParamType::Stage) return spec.default_value;
  YAML::Node name(std::get<std::string>(spec.default_value));
  auto nested = stage(name, spec.stage_role);
  if (!nested) {
    check_.error(owner, fmt::format("the default '{}' for parameter '{}' is not available; give one explicitly",
                                    name.Scalar(), spec.name));
    return std::nullopt;
  }
  return make_ref(std::move(*nested));
}

ParamValue StageValidator::make_ref(StageConfig nested) {
  auto ref = std::make_shared<StageRef>();
  ref->plugin = nested.plugin;
  ref->params = std::move(nested.params);
  ref->instance = std::move(nested.instance);
  return ref;
}

std::optional<ParamValue> StageValidator::parse(const ParamSpec& spec, const YAML::Node& node, const std::string& plugin) {
  const std::string label = fmt::format("parameter '{}' of '{}'", spec.name, plugin);
  if (spec.type == ParamType::Stage) {
    auto nested = stage(node, spec.stage_role);
    if (!nested) return std::nullopt;
    return make_ref(std::move(*nested));
  }
  if (!node.IsScalar()) {
    check_.error(node, fmt::format("{} must be a single {} value", label, to_string(spec.type)));
    return std::nullopt;
  }
  const std::string& text = node.Scalar();
  const auto mistyped = [&]() -> std::optional<ParamValue> {
    check_.error(node, fmt::format("{} must be {} but is '{}'", label,
                                   spec.type == ParamType::Int ? "a whole number"
                                   : spec.type == ParamType::Real ? "a number"
                                                                  : "true or false",
                                   text));
    return std::nullopt;
  };
  const auto in_range = [&](double v) {
    if ((spec.min && v < *spec.min) || (spec.max && v > *spec.max)) {
      check_.error(node, fmt::format("{} is {} but must be {}", label, text, spec.range_text()));
      return false;
    }
    return true;
  };
  switch (spec.type) {
    case ParamType::Bool: {
      auto b = parse_bool(text);
      if (!b) return mistyped();
      return *b;
    }
    case ParamType::Int: {
      auto i = parse_int(text);
      if (!i) return mistyped();
      if (!in_range(static_cast<double>(*i))) return std::nullopt;
      return *i;
    }
    case ParamType::Real: {
      auto r = parse_real(text);
      if (!r) return mistyped();
      if (!in_range(*r)) return std::nullopt;
      return *r;
    }
    case ParamType::Choice:
      if (std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end()) {
        check_.error(node, fmt::format("{} is '{}' but must be {}{}", label, text, spec.range_text(),
                                       did_you_mean(closest_names(text, spec.choices))));
        return std::nullopt;
      }
      return text;
    case ParamType::String:
      return text;
    case ParamType::Stage:
      break;
  }
  return std::nullopt;
}

}  // namespace medax::detail
