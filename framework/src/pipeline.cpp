// Reading and validating pipeline YAML. Every problem is collected (not only the first), each
// with file:line:column and what to do, before any work starts.
#include <medax/kernel/pipeline.hpp>

#include "diagnostics.hpp"
#include "suggest.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

namespace medax {

namespace fs = std::filesystem;

namespace {

// `inputs`, `sweep`, `plots`, `limits` and `table` belong to experiments (sweep_config.cpp); a single run
// ignores them.
const std::vector<std::string> kTopKeys{"medax", "name",  "seed",  "input",  "medial_input", "stages",
                                        "outputs", "inputs", "sweep", "plots", "limits", "table"};
const std::vector<std::string> kStageKeys{"plugin", "id", "params", "enabled"};
const std::vector<std::string> kOutputKeys{"medial", "surface", "frame"};
const std::vector<std::string> kMedialFormats{"ma", "ply", "obj"};
const std::vector<std::string> kSurfaceFormats{"off", "obj", "ply", "stl"};

/// "an extraction stage", "a significance stage": the role with its article.
std::string a_stage(Role role) {
  const std::string_view name = to_string(role);
  const bool vowel = std::string_view("aeiou").find(name.front()) != std::string_view::npos;
  return fmt::format("{} {} stage", vowel ? "an" : "a", name);
}

std::optional<std::string> scalar(detail::Diagnostics& check, const YAML::Node& node, const char* what) {
  if (!node.IsScalar()) {
    check.error(node, fmt::format("{} must be a single value", what));
    return std::nullopt;
  }
  return node.Scalar();
}

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

class Validator {
 public:
  Validator(detail::Diagnostics& check, const Registry& registry) : check_(check), registry_(registry) {}

  /// Validates a stage entry (map with plugin/id/params, or a bare plugin name for nested
  /// stages) and creates its configured instance. Returns nullopt when invalid.
  std::optional<StageConfig> stage(const YAML::Node& node, std::optional<Role> required_role) {
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

 private:
  /// The registered plugin a stage names, of the required role; nullptr (reported) otherwise.
  const RegisteredStage* plugin_of(const YAML::Node& node, const YAML::Node& plugin_node,
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
                                            detail::did_you_mean(registry_.suggest(*name))));
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

  /// True when `params:` is absent, or a map whose every key the plugin declares.
  bool params_declared(const YAML::Node& params_node, const StageInfo& info) {
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
                                         info.name, key, detail::did_you_mean(detail::closest_names(key, declared)),
                                         info.name));
      ok = false;
    }
    return ok;
  }

  /// Every declared parameter: its given value, parsed, or its default.
  bool bind_params(const YAML::Node& node, const YAML::Node& params_node, const StageInfo& info, ParamSet& params) {
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

  /// Creates and configures the stage; its own parameter check's complaint is reported.
  std::optional<StageConfig> instantiate(const RegisteredStage& registered, const YAML::Node& plugin_node,
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

 private:
  std::optional<ParamValue> default_of(const ParamSpec& spec, const YAML::Node& owner) {
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

  static ParamValue make_ref(StageConfig nested) {
    auto ref = std::make_shared<StageRef>();
    ref->plugin = nested.plugin;
    ref->params = std::move(nested.params);
    ref->instance = std::move(nested.instance);
    return ref;
  }

  std::optional<ParamValue> parse(const ParamSpec& spec, const YAML::Node& node, const std::string& plugin) {
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
                                         detail::did_you_mean(detail::closest_names(text, spec.choices))));
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

  detail::Diagnostics& check_;
  const Registry& registry_;
};

/// Why `name` cannot name a folder inside medax-runs/, or nullopt when it can.
std::optional<std::string> name_problem(const std::string& name) {
  if (name.empty()) return std::string("is empty");
  for (const char c : name) {
    if (c == '/' || c == '\\') return fmt::format("'{}' contains the path separator '{}'", name, c);
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return fmt::format("'{}' contains a control character", name);
  }
  if (name.find("..") != std::string::npos) return fmt::format("'{}' contains '..'", name);
  if (name == ".") return std::string("'.' is not a folder name");
  return std::nullopt;
}

fs::path resolve_path(const fs::path& base_dir, const std::string& text) {
  fs::path p(text);
  if (p.is_relative()) p = base_dir / p;
  return fs::absolute(p).lexically_normal();
}

/// The order rules of a stage list, checked stage by stage: conditioning before the first
/// extraction (and not at all after `medial_input:`), an extraction or `medial_input:` (not both)
/// before any other role, and every part of the shape a stage needs made by an earlier stage.
class StageOrder {
 public:
  StageOrder(fs::path medial_input, detail::Diagnostics& check)
      : medial_input_(std::move(medial_input)), has_medial_(!medial_input_.empty()), check_(check) {}

  /// An extraction stage that failed validation: later stages still count on its complex.
  void assume_extraction(const std::string& plugin) {
    has_medial_ = true;
    if (extraction_.empty()) extraction_ = plugin;
  }

  void check(const YAML::Node& node, const StageConfig& stage) {
    const YAML::Node& where = node.IsMap() && node["plugin"] ? node["plugin"] : node;
    if (stage.role == Role::Conditioning && has_medial_) late_conditioning(where, stage.plugin);
    if (stage.role == Role::Extraction) {
      if (!medial_input_.empty())
        check_.error(where, fmt::format("`{}` (extraction) replaces the medial complex read from `medial_input:` "
                                        "{}, which would be silently unused; remove one of the two",
                                        stage.plugin, medial_input_.filename().string()));
      assume_extraction(stage.plugin);
    } else if (stage.role != Role::Conditioning && !has_medial_) {
      check_.error(node, fmt::format("'{}' is {} and needs a medial complex: put an extraction stage "
                                     "before it, or give `medial_input: FILE.ma`",
                                     stage.plugin, a_stage(stage.role)));
    }
    shape_parts(node, stage);
  }

 private:
  /// Conditioning changes the surface, not a complex already built or read: the two would
  /// disagree (normalize after voronoi gave an axis at twice the scale).
  void late_conditioning(const YAML::Node& where, const std::string& plugin) {
    check_.error(where, extraction_.empty()
                            ? fmt::format("`{}` (conditioning) comes after `medial_input:`: conditioning changes the "
                                          "shape but not the medial complex read from {}, so the two would disagree; "
                                          "remove `{}`, or drop `medial_input:` and extract the axis after it",
                                          plugin, medial_input_.filename().string(), plugin)
                            : fmt::format("`{}` (conditioning) comes after `{}` (extraction): conditioning changes "
                                          "the shape but not the medial complex, so the two would disagree; move it "
                                          "before the extraction",
                                          plugin, extraction_));
  }

  void shape_parts(const YAML::Node& node, const StageConfig& stage) {
    if (!stage.instance) return;
    for (ShapePart part : stage.instance->needs())
      if (!made_.count(part))
        check_.error(node, fmt::format("'{}' needs the shape's {} with these parameters, and no stage before it "
                                       "makes them: add one that does (e.g. `sample`) before it, or change its "
                                       "parameters",
                                       stage.plugin, to_string(part)));
    for (ShapePart part : stage.instance->makes()) made_.insert(part);
  }

  fs::path medial_input_;
  bool has_medial_;
  std::string extraction_;  // the first extraction stage; empty while the complex is only medial_input's
  std::set<ShapePart> made_;
  detail::Diagnostics& check_;
};

void apply_overrides(YAML::Node& root, const Overrides& overrides, detail::Diagnostics& check) {
  for (std::size_t i = 0; i < overrides.settings.size(); ++i) {
    const std::string& setting = overrides.settings[i];
    const std::string where =
        fmt::format("{} {}", i < overrides.from_command_line ? "--set" : overrides.origin, setting);
    const auto eq = setting.find('=');
    const auto dot = setting.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq) {
      check.error_at(where, "expected STAGE.PARAM=VALUE, STAGE being a stage id (default: its plugin name)");
      continue;
    }
    const std::string stage_id = setting.substr(0, dot);
    const std::string param = setting.substr(dot + 1, eq - dot - 1);
    const std::string value = setting.substr(eq + 1);
    bool found = false;
    std::vector<std::string> ids;
    if (root["stages"] && root["stages"].IsSequence()) {
      for (YAML::Node stage : root["stages"]) {
        if (!stage.IsMap()) continue;
        // Scalar() is empty for a malformed id or plugin; validation reports those.
        const std::string id = stage["id"] ? stage["id"].Scalar() : stage["plugin"] ? stage["plugin"].Scalar() : "";
        ids.push_back(id);
        if (id != stage_id) continue;
        found = true;
        if (param == "enabled") {
          YAML::Node flag = YAML::Node(value);
          stage["enabled"] = flag;
          check.mark_overridden(flag, where);
          continue;
        }
        if (param == "plugin") {  // swap the plugin; the old plugin's params do not apply
          YAML::Node plugin = YAML::Node(value);
          stage["plugin"] = plugin;
          stage.remove("params");
          check.mark_overridden(stage["plugin"], where);
          continue;
        }
        YAML::Node params = stage["params"];
        if (!params || params.IsNull()) params = YAML::Node(YAML::NodeType::Map);
        YAML::Node parsed;
        try {
          parsed = YAML::Load(value);
        } catch (const YAML::Exception& e) {
          check.error_at(where, fmt::format("the value is not valid YAML: {}", e.msg));
          continue;
        }
        params[param] = parsed;
        stage["params"] = params;
        check.mark_overridden(parsed, where);
        for (const auto& kv : params)  // the key too, so "no parameter 'x'" names the option
          if (kv.first.Scalar() == param) check.mark_overridden(kv.first, where);
      }
    }
    if (!found)
      check.error_at(where, fmt::format("no stage with id '{}'{}", stage_id,
                                        detail::did_you_mean(detail::closest_names(stage_id, ids))));
  }
}

std::vector<std::string> formats(detail::Diagnostics& check, const YAML::Node& node, const std::vector<std::string>& allowed,
                                 const char* what) {
  std::vector<std::string> out;
  const auto add = [&](const YAML::Node& n) {
    if (!n.IsScalar()) return check.error(n, fmt::format("{} formats are names like {}", what, allowed[0]));
    if (std::find(allowed.begin(), allowed.end(), n.Scalar()) == allowed.end())
      return check.error(n, fmt::format("unknown {} format '{}'; use {}", what, n.Scalar(), fmt::join(allowed, ", ")));
    out.push_back(n.Scalar());
  };
  if (node.IsSequence()) for (const auto& n : node) add(n);
  else add(node);
  return out;
}

}  // namespace

namespace {
/// fs::exists without its exception: a path the system refuses (a name too long) is not found.
bool file_exists(const fs::path& path) {
  std::error_code ignored;
  return fs::exists(path, ignored);
}

YAML::Node read_root(const fs::path& file) {
  if (!file_exists(file)) throw PipelineError({Diagnostic{file.string(), 0, 0, "no such pipeline file"}});
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw PipelineError({Diagnostic{file.string(), e.mark.line + 1, e.mark.column + 1,
                                    "not valid YAML: " + e.msg}});
  }
  if (!root.IsMap())
    throw PipelineError({Diagnostic{file.string(), 1, 1, "a pipeline is a YAML map with `input:` and `stages:`"}});
  return root;
}

/// `name` (else the file's stem), `medax` (the format version) and `seed`.
void load_header(detail::Diagnostics& check, const YAML::Node& root, const fs::path& file, PipelineConfig& config) {
  config.name = file.stem().string();
  if (!root["name"] && name_problem(config.name))  // a file named `...yaml` has the stem `..`
    check.error_at(file.string(), fmt::format("the file's name '{}' cannot name a run folder; add `name: NAME` "
                                              "(letters, digits, '-' and '_')", config.name));
  if (root["name"]) {
    if (auto name = scalar(check, root["name"], "`name`")) {
      config.name = *name;
      // The default run folder is medax-runs/<name>-<input stem> (and a sweep's medax-runs/<name>):
      // a separator or `..` would put it elsewhere.
      if (const auto problem = name_problem(*name))
        check.error(root["name"],
                    fmt::format("`name` {}: it names the run folder (medax-runs/<name>-<input>; an experiment's "
                                "medax-runs/<name>), so it must be one folder name: any characters but '/', '\\' and "
                                "control characters, without '..' (e.g. letters, digits, '-' and '_')",
                                *problem));
    }
  }
  if (root["medax"] && root["medax"].Scalar() != "1")
    check.error(root["medax"], "this medax reads pipeline format 1; `medax: " + root["medax"].Scalar() + "` is newer");
  if (root["seed"]) {
    auto s = parse_int(root["seed"].Scalar());
    if (!s || *s < 0) check.error(root["seed"], "`seed` must be a whole number >= 0");
    else config.seed = static_cast<std::uint64_t>(*s);
  }
}

/// The input mesh (`--input` wins over `input:`) and the optional `medial_input`, relative to
/// the pipeline file.
void load_inputs(detail::Diagnostics& check, const YAML::Node& root, const fs::path& file, const Overrides& overrides,
                 PipelineConfig& config) {
  const fs::path base = config.file.parent_path();
  if (!overrides.input.empty()) {
    config.input = fs::absolute(overrides.input).lexically_normal();
    if (!file_exists(config.input)) check.error_at("--input", fmt::format("input file {} not found", config.input.string()));
  } else if (root["input"]) {
    if (auto text = scalar(check, root["input"], "`input`")) {
      config.input = resolve_path(base, *text);
      if (!file_exists(config.input))
        check.error(root["input"], fmt::format("input file {} not found (paths are relative to the pipeline file)",
                                               config.input.string()));
    }
  } else {
    check.error_at(file.string(), "no input mesh: add `input: PATH` or run with --input PATH");
  }
  if (root["medial_input"]) {
    if (auto text = scalar(check, root["medial_input"], "`medial_input`")) {
      config.medial_input = resolve_path(base, *text);
      if (!file_exists(config.medial_input))
        check.error(root["medial_input"], fmt::format("medial input {} not found", config.medial_input.string()));
    }
  }
}

/// False for a stage written with `enabled: false` (or --set STAGE.enabled=false).
bool stage_enabled(detail::Diagnostics& check, const YAML::Node& node) {
  if (!node.IsMap() || !node["enabled"]) return true;
  const auto enabled = parse_bool(node["enabled"].Scalar());
  if (!enabled) check.error(node["enabled"], "`enabled` is true or false");
  return enabled.value_or(true);
}

void load_stages(detail::Diagnostics& check, const YAML::Node& root, const Registry& registry, PipelineConfig& config) {
  const YAML::Node stages = root["stages"];
  if (!stages || !stages.IsSequence() || stages.size() == 0) {
    check.error(stages ? stages : root, "`stages:` must be a non-empty list of stages");
    return;
  }
  Validator validator(check, registry);
  StageOrder order(config.medial_input, check);
  std::set<std::string> ids;
  for (const YAML::Node& node : stages) {
    if (!stage_enabled(check, node)) continue;
    auto stage = validator.stage(node, std::nullopt);
    if (!stage) {
      // An invalid extraction stage still provides the complex for the role check of later
      // stages, so one mistake is not reported twice.
      if (node.IsMap() && node["plugin"] && node["plugin"].IsScalar())
        if (const RegisteredStage* s = registry.find(node["plugin"].Scalar()))
          if (s->info().role == Role::Extraction) order.assume_extraction(s->info().name);
      continue;
    }
    if (!ids.insert(stage->id).second)
      check.error(node, fmt::format("two stages have the id '{}'; give one of them `id: OTHER`", stage->id));
    order.check(node, *stage);
    config.stages.push_back(std::move(*stage));
  }
}

void load_outputs(detail::Diagnostics& check, const YAML::Node& root, PipelineConfig& config) {
  const YAML::Node outputs = root["outputs"];
  if (!outputs) {
    config.outputs.medial = {"ma", "ply"};
    return;
  }
  if (!outputs.IsMap()) return check.error(outputs, "`outputs:` is a map like {medial: [ma, ply], surface: [off]}");
  check.unknown_keys(outputs, kOutputKeys, "outputs");
  if (outputs["medial"]) config.outputs.medial = formats(check, outputs["medial"], kMedialFormats, "medial");
  if (outputs["surface"]) config.outputs.surface = formats(check, outputs["surface"], kSurfaceFormats, "surface");
  if (outputs["frame"]) {
    const std::string frame = outputs["frame"].Scalar();
    if (frame != "input" && frame != "working")
      check.error(outputs["frame"], "`frame` is `input` (the input file's coordinates) or `working`");
    config.outputs.input_frame = frame == "input";
  }
}

PipelineConfig load_checked(const fs::path& file, const Registry& registry, const Overrides& overrides) {
  detail::Diagnostics check(file.string());
  YAML::Node root = read_root(file);
  check.duplicate_keys(root);  // before the overrides add nodes
  apply_overrides(root, overrides, check);
  check.unknown_keys(root, kTopKeys, "pipeline");

  PipelineConfig config;
  config.file = fs::absolute(file).lexically_normal();
  load_header(check, root, file, config);
  load_inputs(check, root, file, overrides, config);
  load_stages(check, root, registry, config);
  load_outputs(check, root, config);
  if (!check.ok()) throw PipelineError(check.take());
  return config;
}
}  // namespace

PipelineConfig load_pipeline(const fs::path& file, const Registry& registry, const Overrides& overrides) {
  try {
    return load_checked(file, registry, overrides);
  } catch (const YAML::Exception& e) {
    // A shape of YAML the checks above did not anticipate: still one diagnostic, never a crash.
    if (e.mark.is_null()) throw PipelineError({Diagnostic{file.string(), 0, 0, "unexpected structure: " + e.msg}});
    throw PipelineError({Diagnostic{file.string(), e.mark.line + 1, e.mark.column + 1,
                                    "unexpected structure: " + e.msg}});
  }
}

}  // namespace medax
