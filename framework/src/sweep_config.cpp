// Reading the experiment parts of a pipeline (`inputs:`, `sweep:`, `plots:`, `limits:`) and
// expanding them into jobs.
#include <medax/kernel/sweep.hpp>

#include "diagnostics.hpp"

#include <fmt/format.h>
#include <glob.h>
#include <yaml-cpp/yaml.h>

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

/// One entry of `inputs:`: a path, a glob, or {manifest: FILE} (one path per line, '#' comments).
void add_inputs(const YAML::Node& node, const fs::path& base, std::vector<fs::path>& inputs, detail::Diagnostics& diag) {
  if (node.IsMap() && node["manifest"] && node["manifest"].IsScalar()) {
    const fs::path manifest = absolute_from(base, node["manifest"].Scalar());
    std::ifstream in(manifest);
    if (!in) return diag.error(node["manifest"], fmt::format("cannot read manifest {}", manifest.string()));
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      line = line.substr(0, line.find('#'));
      line.erase(0, line.find_first_not_of(" \t"));
      line.erase(line.find_last_not_of(" \t\r") + 1);
      if (line.empty()) continue;
      const fs::path p = absolute_from(manifest.parent_path(), line);
      if (!fs::exists(p))
        diag.error(node["manifest"], fmt::format("{}:{}: input {} not found", manifest.string(), number, p.string()));
      inputs.push_back(p);
    }
    return;
  }
  if (!node.IsScalar())
    return diag.error(node, "an `inputs:` entry is a path, a glob like meshes/*.off, or {manifest: FILE}");
  const fs::path p = absolute_from(base, node.Scalar());
  if (has_glob_characters(node.Scalar())) {
    const auto matches = glob_paths(p);
    if (matches.empty()) diag.error(node, fmt::format("no file matches {}", p.string()));
    inputs.insert(inputs.end(), matches.begin(), matches.end());
  } else {
    if (!fs::exists(p)) diag.error(node, fmt::format("input file {} not found", p.string()));
    inputs.push_back(p);
  }
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
  const fs::path base = config.file.parent_path();
  config.name = root["name"] && root["name"].IsScalar() ? root["name"].Scalar() : pipeline.stem().string();

  if (const YAML::Node inputs = root["inputs"]) {
    if (inputs.IsSequence()) for (const YAML::Node& n : inputs) add_inputs(n, base, config.inputs, diag);
    else add_inputs(inputs, base, config.inputs, diag);
    if (root["input"]) diag.error(root["input"], "give either `input:` or `inputs:`, not both");
  } else if (root["input"] && root["input"].IsScalar()) {
    config.inputs.push_back(absolute_from(base, root["input"].Scalar()));
  } else {
    diag.error(root, "an experiment needs `input:` or `inputs:`");
  }

  if (const YAML::Node sweep = root["sweep"]) {
    if (!sweep.IsMap()) diag.error(sweep, "`sweep:` maps STAGE.PARAM (or STAGE.plugin, or a name) to a list of values");
    else {
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
    }
  }

  if (const YAML::Node plots = root["plots"]) {
    if (!plots.IsSequence()) diag.error(plots, "`plots:` is a list of {x: COLUMN, y: COLUMN}");
    else
      for (const YAML::Node& p : plots) {
        if (!p.IsMap() || !p["x"] || !p["y"]) {
          diag.error(p, "a plot is {x: COLUMN, y: COLUMN, series: COLUMN, log_x: bool, log_y: bool, style: lines|points}");
          continue;
        }
        PlotSpec spec{p["x"].Scalar(), p["y"].Scalar(), p["series"] ? p["series"].Scalar() : "input"};
        spec.log_x = p["log_x"] && p["log_x"].as<bool>(false);
        spec.log_y = p["log_y"] && p["log_y"].as<bool>(false);
        if (p["style"]) {
          if (p["style"].Scalar() != "points" && p["style"].Scalar() != "lines")
            diag.error(p["style"], "a plot's `style` is `lines` (curves through the points) or `points` (a scatter)");
          spec.points_only = p["style"].Scalar() == "points";
        }
        config.plots.push_back(spec);
      }
  }

  if (const YAML::Node table = root["table"]) {
    if (!table.IsSequence()) diag.error(table, "`table:` is the list of results.csv columns results.md shows");
    else
      for (const YAML::Node& c : table) config.table_columns.push_back(c.Scalar());
  }

  if (const YAML::Node limits = root["limits"]) {
    const auto positive = [&](const char* key, double& out) {
      if (!limits[key]) return;
      try {
        out = limits[key].as<double>();
        if (out < 0) diag.error(limits[key], fmt::format("`{}` must be >= 0", key));
      } catch (const YAML::Exception&) {
        diag.error(limits[key], fmt::format("`{}` must be a number", key));
      }
    };
    if (!limits.IsMap())
      diag.error(limits, "`limits:` is {timeout: SECONDS, memory_mib: MIB, interrupt_grace: SECONDS}");
    else {
      positive("timeout", config.limits.timeout_seconds);
      positive("memory_mib", config.limits.memory_mib);
      positive("interrupt_grace", config.limits.interrupt_grace_seconds);
    }
  }
  diag.throw_if_any();
  return config;
}

std::vector<SweepJob> expand_sweep(const SweepConfig& config) {
  std::vector<SweepJob> jobs;
  std::vector<std::size_t> choice(config.axes.size(), 0);
  for (const fs::path& input : config.inputs) {
    std::fill(choice.begin(), choice.end(), 0);
    while (true) {
      SweepJob job;
      job.input = input;
      std::string name = fmt::format("{:04}-{}", jobs.size() + 1, input.stem().string());
      for (std::size_t a = 0; a < config.axes.size(); ++a) {
        const SweepAxis& axis = config.axes[a];
        job.assignment.emplace_back(axis.key, axis.values[choice[a]]);
        job.settings.insert(job.settings.end(), axis.settings[choice[a]].begin(), axis.settings[choice[a]].end());
        name += "-" + axis.key.substr(axis.key.find('.') + 1) + "=" + axis.values[choice[a]];
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
                                                                Overrides{job.input, job.settings, "sweep"})));
    } catch (const PipelineError& e) {
      for (const Diagnostic& d : e.diagnostics())
        if (seen.insert(d.format()).second) all.push_back(d);
    }
  }
  if (!all.empty()) throw PipelineError(std::move(all));
}

}  // namespace medax
