// Reading and validating pipeline YAML. Every problem is collected (not only the first), each
// with file:line:column and what to do, before any work starts.
#include <medax/kernel/pipeline.hpp>

#include "diagnostics.hpp"
#include "stage_validator.hpp"
#include "suggest.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

namespace medax {

namespace fs = std::filesystem;

using detail::a_stage;
using detail::parse_bool;
using detail::parse_int;
using detail::scalar;

namespace {

// `inputs`, `sweep`, `plots`, `limits` and `table` belong to experiments (sweep_config.cpp); a single run
// ignores them.
const std::vector<std::string> kTopKeys{"medax", "name",  "seed",  "input",  "medial_input", "stages",
                                        "outputs", "inputs", "sweep", "plots", "limits", "table"};
const std::vector<std::string> kOutputKeys{"medial", "surface", "frame"};
const std::vector<std::string> kMedialFormats{"ma", "ply", "obj"};
const std::vector<std::string> kSurfaceFormats{"off", "obj", "ply", "stl"};


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
  detail::StageValidator validator(check, registry);
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
