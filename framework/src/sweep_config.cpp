// Reading the experiment parts of a pipeline (`inputs:`, `sweep:`, `plots:`, `limits:`) and
// expanding them into jobs.
#include <medax/kernel/sweep.hpp>

#include "diagnostics.hpp"

#include <fmt/format.h>
#include <glob.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <optional>
#include <set>

namespace medax {

namespace fs = std::filesystem;

namespace {

std::string yaml_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

bool has_glob_characters(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

std::vector<fs::path> glob_paths(const fs::path& pattern) {
  glob_t result{};
  std::vector<fs::path> out;
  if (::glob(pattern.c_str(), 0, nullptr, &result) == 0)
    for (std::size_t i = 0; i < result.gl_pathc; ++i) out.emplace_back(result.gl_pathv[i]);
  ::globfree(&result);
  std::sort(out.begin(), out.end());
  return out;
}

fs::path absolute_from(const fs::path& base, const std::string& text) {
  fs::path p(text);
  return (p.is_relative() ? base / p : p).lexically_normal();
}

bool is_variable_name(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

/// A manifest line: the input's path, then optional NAME=VALUE words (that input's variables).
struct ManifestLine {
  std::string path;
  std::map<std::string, std::string> variables;
  std::string twice;  ///< a variable given twice on the line, if any
};

ManifestLine parse_manifest_line(std::string line) {
  ManifestLine out;
  // Words are taken from the end while they look like NAME=VALUE, so a path may hold spaces.
  for (auto space = line.find_last_of(" \t"); space != std::string::npos; space = line.find_last_of(" \t")) {
    const std::string word = line.substr(space + 1);
    const auto eq = word.find('=');
    if (eq == std::string::npos || !is_variable_name(word.substr(0, eq))) break;
    if (!out.variables.emplace(word.substr(0, eq), word.substr(eq + 1)).second) out.twice = word.substr(0, eq);
    const auto end = line.find_last_not_of(" \t", space);
    line.erase(end == std::string::npos ? 0 : end + 1);
  }
  out.path = line;
  return out;
}

/// `{manifest: FILE}`: one input per line (a path, then optional NAME=VALUE variables), '#' comments.
void add_manifest(const YAML::Node& at, const fs::path& manifest, SweepConfig& config, detail::Diagnostics& diag) {
  std::ifstream in(manifest);
  if (!in) return diag.error(at, fmt::format("cannot read manifest {}", manifest.string()));
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    text = text.substr(0, text.find('#'));
    text.erase(0, text.find_first_not_of(" \t"));
    text.erase(text.find_last_not_of(" \t\r") + 1);
    if (text.empty()) continue;
    const std::string where = fmt::format("{}:{}", manifest.string(), number);
    const ManifestLine line = parse_manifest_line(text);
    if (line.path.empty()) diag.error(at, fmt::format("{}: a manifest line starts with the input's path", where));
    if (!line.twice.empty())
      diag.error(at, fmt::format("{}: variable '{}' is given twice on this line; keep one", where, line.twice));
    const fs::path p = absolute_from(manifest.parent_path(), line.path);
    if (!fs::exists(p)) diag.error(at, fmt::format("{}: input {} not found", where, p.string()));
    const auto [it, fresh] = config.variables.emplace(p, InputVariables{line.variables, where});
    if (!fresh && it->second.values != line.variables)
      diag.error(at, fmt::format("{}: input {} is listed again with other variables (first at {}); a sweep's "
                                 "variables belong to the input, so list it once",
                                 where, p.string(), it->second.origin));
    config.inputs.push_back(p);
  }
}

/// One entry of `inputs:`: a path, a glob, or {manifest: FILE}.
void add_inputs(const YAML::Node& node, const fs::path& base, SweepConfig& config, detail::Diagnostics& diag) {
  if (node.IsMap() && node["manifest"] && node["manifest"].IsScalar())
    return add_manifest(node["manifest"], absolute_from(base, node["manifest"].Scalar()), config, diag);
  if (!node.IsScalar())
    return diag.error(node, "an `inputs:` entry is a path, a glob like meshes/*.off, or {manifest: FILE}");
  const fs::path p = absolute_from(base, node.Scalar());
  if (has_glob_characters(node.Scalar())) {
    const auto matches = glob_paths(p);
    if (matches.empty()) diag.error(node, fmt::format("no file matches {}", p.string()));
    config.inputs.insert(config.inputs.end(), matches.begin(), matches.end());
  } else {
    if (!fs::exists(p)) diag.error(node, fmt::format("input file {} not found", p.string()));
    config.inputs.push_back(p);
  }
}

/// A sweep value with its `${NAME}` references replaced by an input's variables; `${NAME:-TEXT}`
/// gives TEXT to an input that does not set NAME.
struct Expansion {
  std::string text;
  std::vector<std::string> undefined;  ///< names the input does not define (and no default)
  bool malformed = false;              ///< a `${` without `}` or with something other than a name
};

Expansion expand_variables(const std::string& text, const std::map<std::string, std::string>& values) {
  Expansion out;
  std::size_t from = 0;
  for (auto open = text.find("${"); open != std::string::npos; open = text.find("${", from)) {
    const auto close = text.find('}', open);
    const std::string inside = close == std::string::npos ? "" : text.substr(open + 2, close - open - 2);
    const auto dash = inside.find(":-");
    const std::string name = inside.substr(0, dash);
    out.text += text.substr(from, open - from);
    if (!is_variable_name(name)) {
      out.malformed = true;
      from = open;
      break;
    }
    const auto it = values.find(name);
    if (it != values.end()) out.text += it->second;
    else if (dash != std::string::npos) out.text += inside.substr(dash + 2);
    else {
      out.undefined.push_back(name);
      out.text += text.substr(open, close + 1 - open);
    }
    from = close + 1;
  }
  out.text += text.substr(from);
  return out;
}

const std::map<std::string, std::string>& variables_of(const SweepConfig& config, const fs::path& input) {
  static const std::map<std::string, std::string> none;
  const auto it = config.variables.find(input);
  return it == config.variables.end() ? none : it->second.values;
}

/// "plane.off (list.txt:4)" or "plane.off (given as a path, which sets no variables)".
std::string input_origin(const SweepConfig& config, const fs::path& input) {
  const auto it = config.variables.find(input);
  return fmt::format("{} ({})", input.string(),
                     it == config.variables.end() ? "not from a manifest line, so it has no variables" : it->second.origin);
}

std::string undefined_message(const std::string& name, const std::vector<std::string>& inputs) {
  std::string list;
  for (const std::string& input : inputs) list += (list.empty() ? "" : "; ") + input;
  return fmt::format("unknown variable '${{{}}}': not defined for input {}; write `{}=VALUE` after the input's "
                     "path on its manifest line, or give a default: ${{{}:-VALUE}}",
                     name, list, name, name);
}

/// Every `${NAME}` in the sweep's values (bundle names too) must be defined for every input.
void check_variable_uses(const YAML::Node& node, const SweepConfig& config, detail::Diagnostics& diag) {
  if (node.IsMap()) {
    for (const auto& kv : node) check_variable_uses(kv.second, config, diag);
    return;
  }
  if (node.IsSequence()) {
    for (const YAML::Node& n : node) check_variable_uses(n, config, diag);
    return;
  }
  if (!node.IsScalar() || node.Scalar().find("${") == std::string::npos) return;
  std::map<std::string, std::vector<std::string>> lacking;  // variable -> inputs that do not set it
  for (const fs::path& input : config.inputs) {
    const Expansion e = expand_variables(node.Scalar(), variables_of(config, input));
    if (e.malformed)
      return diag.error(node, fmt::format("'{}': a variable is written ${{NAME}} or ${{NAME:-DEFAULT}}, NAME made of letters, "
                                          "digits and _",
                                          node.Scalar()));
    for (const std::string& name : e.undefined) lacking[name].push_back(input_origin(config, input));
  }
  for (const auto& [name, inputs] : lacking) diag.error(node, undefined_message(name, inputs));
}

/// `STAGE.PARAM: [v1, v2]` (or a single value).
SweepAxis plain_axis(const std::string& key, const YAML::Node& values) {
  SweepAxis axis{key, {}, {}};
  const auto add = [&](const YAML::Node& v) {
    axis.values.push_back(yaml_text(v));
    axis.settings.push_back({key + "=" + axis.values.back()});
  };
  if (values.IsSequence()) for (const YAML::Node& v : values) add(v);
  else add(values);
  return axis;
}

/// `NAME: [{name: a, STAGE.X: v, ...}, ...]`: bundles of settings applied together.
std::optional<SweepAxis> named_axis(const YAML::Node& key, const YAML::Node& values, detail::Diagnostics& diag) {
  SweepAxis axis{key.Scalar(), {}, {}};
  if (!values.IsSequence()) {
    diag.error(values, fmt::format("sweep key '{}' has no dot, so it names a list of bundles like "
                                   "[{{name: a, STAGE.PARAM: v}}]; or write STAGE.PARAM", axis.key));
    return std::nullopt;
  }
  bool ok = true;
  for (const YAML::Node& bundle : values) {
    if (!bundle.IsMap()) {
      diag.error(bundle, "a bundle is a map {name: LABEL, STAGE.PARAM: VALUE, ...}");
      ok = false;
      continue;
    }
    std::string name = bundle["name"] ? bundle["name"].Scalar() : std::to_string(axis.values.size() + 1);
    std::vector<std::string> settings;
    for (const auto& kv : bundle) {
      const std::string k = kv.first.Scalar();
      if (k == "name") continue;
      if (k.find('.') == std::string::npos) diag.error(kv.first, fmt::format("'{}' must be STAGE.PARAM or STAGE.plugin", k));
      settings.push_back(k + "=" + yaml_text(kv.second));
    }
    // A plugin swap resets that stage's parameters, so it must come first.
    std::stable_partition(settings.begin(), settings.end(),
                          [](const std::string& s) { return s.find(".plugin=") != std::string::npos; });
    axis.values.push_back(name);
    axis.settings.push_back(std::move(settings));
  }
  if (!ok) return std::nullopt;
  return axis;
}

/// The STAGE.PARAM (or STAGE.plugin) keys an axis sets: its own key, or every key its bundles set.
std::set<std::string> keys_set_by(const SweepAxis& axis) {
  std::set<std::string> keys;
  for (const auto& settings : axis.settings)
    for (const std::string& s : settings) keys.insert(s.substr(0, s.find('=')));
  return keys;
}

/// FNV-1a, 64 bits, as 16 hex digits: an identity for resume, not a security measure.
std::string config_hash(const std::string& text) {
  std::uint64_t h = 0xCBF29CE484222325ull;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001B3ull;
  return fmt::format("{:016x}", h);
}

std::string folder_safe(const std::string& text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-') ? c : '_';
  return out;
}

}  // namespace

bool is_sweep(const fs::path& pipeline) {
  try {
    const YAML::Node root = YAML::LoadFile(pipeline.string());
    return root.IsMap() && (root["sweep"] || root["inputs"]);
  } catch (const YAML::Exception&) {
    return false;  // load_pipeline reports the syntax error with its position
  }
}

namespace {

void load_inputs(const YAML::Node& root, const fs::path& base, SweepConfig& config, detail::Diagnostics& diag) {
  if (const YAML::Node inputs = root["inputs"]) {
    if (inputs.IsSequence()) for (const YAML::Node& n : inputs) add_inputs(n, base, config, diag);
    else add_inputs(inputs, base, config, diag);
    if (root["input"]) diag.error(root["input"], "give either `input:` or `inputs:`, not both");
  } else if (root["input"] && root["input"].IsScalar()) {
    config.inputs.push_back(absolute_from(base, root["input"].Scalar()));
  } else {
    diag.error(root, "an experiment needs `input:` or `inputs:`");
  }
}

/// The axes of `sweep:`; no STAGE.PARAM may be set by two of them.
void load_axes(const YAML::Node& sweep, SweepConfig& config, detail::Diagnostics& diag) {
  if (!sweep.IsMap())
    return diag.error(sweep, "`sweep:` maps STAGE.PARAM (or STAGE.plugin, or a name) to a list of values");
  std::map<std::string, std::string> axis_setting;  // STAGE.PARAM -> the sweep key that sets it
  for (const auto& kv : sweep) {
    std::optional<SweepAxis> axis = kv.first.Scalar().find('.') == std::string::npos
                                        ? named_axis(kv.first, kv.second, diag)
                                        : plain_axis(kv.first.Scalar(), kv.second);
    if (!axis) continue;
    if (axis->values.empty()) diag.error(kv.second, fmt::format("sweep key '{}' has no values", axis->key));
    for (const std::string& key : keys_set_by(*axis))
      if (const auto [it, fresh] = axis_setting.emplace(key, axis->key); !fresh && it->second != axis->key)
        diag.error(kv.first, fmt::format("sweep key '{}' sets {}, which '{}' sets too: the job's folder and "
                                         "results would name one value while the other runs; set it in one place",
                                         axis->key, key, it->second));
    config.axes.push_back(std::move(*axis));
  }
  check_variable_uses(sweep, config, diag);
}

std::optional<PlotSpec> plot_spec(const YAML::Node& p, detail::Diagnostics& diag) {
  if (!p.IsMap() || !p["x"] || !p["y"]) {
    diag.error(p, "a plot is {x: COLUMN, y: COLUMN, series: COLUMN, log_x: bool, log_y: bool, style: lines|points}");
    return std::nullopt;
  }
  PlotSpec spec{p["x"].Scalar(), p["y"].Scalar(), p["series"] ? p["series"].Scalar() : "input"};
  spec.log_x = p["log_x"] && p["log_x"].as<bool>(false);
  spec.log_y = p["log_y"] && p["log_y"].as<bool>(false);
  if (p["style"]) {
    if (p["style"].Scalar() != "points" && p["style"].Scalar() != "lines")
      diag.error(p["style"], "a plot's `style` is `lines` (curves through the points) or `points` (a scatter)");
    spec.points_only = p["style"].Scalar() == "points";
  }
  return spec;
}

void load_plots(const YAML::Node& plots, SweepConfig& config, detail::Diagnostics& diag) {
  if (!plots.IsSequence()) return diag.error(plots, "`plots:` is a list of {x: COLUMN, y: COLUMN}");
  for (const YAML::Node& p : plots)
    if (auto spec = plot_spec(p, diag)) config.plots.push_back(std::move(*spec));
}

void load_limits(const YAML::Node& limits, SweepLimits& out, detail::Diagnostics& diag) {
  if (!limits.IsMap())
    return diag.error(limits, "`limits:` is {timeout: SECONDS, memory_mib: MIB, interrupt_grace: SECONDS}");
  const auto non_negative = [&](const char* key, double& value) {
    if (!limits[key]) return;
    try {
      value = limits[key].as<double>();
      if (value < 0) diag.error(limits[key], fmt::format("`{}` must be >= 0", key));
    } catch (const YAML::Exception&) {
      diag.error(limits[key], fmt::format("`{}` must be a number", key));
    }
  };
  non_negative("timeout", out.timeout_seconds);
  non_negative("memory_mib", out.memory_mib);
  non_negative("interrupt_grace", out.interrupt_grace_seconds);
}

}  // namespace

SweepConfig load_sweep(const fs::path& pipeline) {
  detail::Diagnostics diag(pipeline.string());
  YAML::Node root;
  try {
    root = YAML::LoadFile(pipeline.string());
  } catch (const YAML::Exception& e) {
    throw PipelineError({Diagnostic{pipeline.string(), e.mark.line + 1, e.mark.column + 1, "not valid YAML: " + e.msg}});
  }
  diag.duplicate_keys(root);
  SweepConfig config;
  config.file = fs::absolute(pipeline).lexically_normal();
  config.name = root["name"] && root["name"].IsScalar() ? root["name"].Scalar() : pipeline.stem().string();
  load_inputs(root, config.file.parent_path(), config, diag);
  if (const YAML::Node sweep = root["sweep"]) load_axes(sweep, config, diag);
  if (const YAML::Node plots = root["plots"]) load_plots(plots, config, diag);
  if (const YAML::Node table = root["table"]) {
    if (!table.IsSequence()) diag.error(table, "`table:` is the list of results.csv columns results.md shows");
    else
      for (const YAML::Node& c : table) config.table_columns.push_back(c.Scalar());
  }
  if (const YAML::Node limits = root["limits"]) load_limits(limits, config.limits, diag);
  diag.throw_if_any();
  return config;
}

std::vector<SweepJob> expand_sweep(const SweepConfig& config) {
  std::vector<SweepJob> jobs;
  std::vector<std::size_t> choice(config.axes.size(), 0);
  for (const fs::path& input : config.inputs) {
    const auto& variables = variables_of(config, input);
    const auto expand = [&](const std::string& text) {
      Expansion e = expand_variables(text, variables);
      if (!e.undefined.empty())  // an input replaced after load_sweep checked the file's own
        throw PipelineError({Diagnostic{config.file.string(), 0, 0,
                                        undefined_message(e.undefined.front(), {input_origin(config, input)})}});
      return e.text;
    };
    std::fill(choice.begin(), choice.end(), 0);
    while (true) {
      SweepJob job;
      job.input = input;
      std::string name = fmt::format("{:04}-{}", jobs.size() + 1, input.stem().string());
      for (std::size_t a = 0; a < config.axes.size(); ++a) {
        const SweepAxis& axis = config.axes[a];
        const std::string shown = expand(axis.values[choice[a]]);
        job.assignment.emplace_back(axis.key, shown);
        for (const std::string& setting : axis.settings[choice[a]]) {
          const auto eq = setting.find('=');
          job.settings.push_back(setting.substr(0, eq + 1) + expand(setting.substr(eq + 1)));
        }
        name += "-" + axis.key.substr(axis.key.find('.') + 1) + "=" + shown;
      }
      // A plugin swap resets that stage's parameters, so swaps go first.
      std::stable_partition(job.settings.begin(), job.settings.end(),
                            [](const std::string& s) { return s.find(".plugin=") != std::string::npos; });
      job.name = folder_safe(name).substr(0, 120);
      jobs.push_back(std::move(job));
      // Odometer over the axes, last axis fastest.
      std::size_t a = config.axes.size();
      while (a > 0 && ++choice[a - 1] == config.axes[a - 1].values.size()) choice[--a] = 0;
      if (a == 0) break;
    }
  }
  return jobs;
}

void validate_sweep(const SweepConfig& config, std::vector<SweepJob>& jobs, const Registry& registry) {
  std::vector<Diagnostic> all;
  std::set<std::string> seen;
  for (SweepJob& job : jobs) {
    try {
      // The resolved YAML holds nothing of the run folder: its hash is the job's configuration.
      job.config_hash = config_hash(resolved_yaml(load_pipeline(config.file, registry,
                                                                Overrides{job.input, job.settings, "sweep",
                                                                          job.from_command_line})));
    } catch (const PipelineError& e) {
      for (const Diagnostic& d : e.diagnostics())
        if (seen.insert(d.format()).second) all.push_back(d);
    }
  }
  if (!all.empty()) throw PipelineError(std::move(all));
}

}  // namespace medax
