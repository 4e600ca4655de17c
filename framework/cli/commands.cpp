#include "commands.hpp"

#include <medax/kernel/param_table.hpp>

#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>
#include <medax/kernel/sweep.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

namespace medax::cli {

namespace {

void print_load_errors(const Registry& registry) {
  for (const std::string& e : registry.errors()) fmt::print(stderr, "error: {}\n", e);
}

/// After an "unknown plugin 'NAME'" diagnostic: the load failure of each plugin file that may
/// have provided NAME.
void print_unknown_plugin_notes(const Diagnostic& d, const Registry& registry) {
  const std::string marker = "unknown plugin '";
  const auto start = d.message.find(marker);
  if (start == std::string::npos) return;
  const auto end = d.message.find('\'', start + marker.size());
  const std::string name = d.message.substr(start + marker.size(), end - start - marker.size());
  for (const std::string& line : registry.failures_for(name))
    fmt::print(stderr, "note: '{}' may be in a plugin file that failed to load: {}\n", name, line);
}

std::size_t widest(const std::vector<std::vector<std::string>>& rows, std::size_t column) {
  std::size_t w = 0;
  for (const auto& row : rows) w = std::max(w, row[column].size());
  return w;
}

void print_table(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> widths;
  for (std::size_t c = 0; c < rows.front().size(); ++c) widths.push_back(widest(rows, c));
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += c + 1 == row.size() ? row[c] : fmt::format("{:<{}}  ", row[c], widths[c]);
    fmt::print("{}\n", line);
  }
}

/// Loads and validates; prints diagnostics and returns nullopt on failure.
std::optional<PipelineConfig> load(const RunArgs& args, const Registry& registry) {
  try {
    return load_pipeline(args.pipeline, registry, Overrides{args.input, args.settings});
  } catch (const PipelineError& e) {
    for (const Diagnostic& d : e.diagnostics()) {
      fmt::print(stderr, "{}\n", d.format());
      print_unknown_plugin_notes(d, registry);
    }
    return std::nullopt;
  }
}

}  // namespace

std::filesystem::path default_run_folder(const PipelineConfig& config) {
  return fmt::format("medax-runs/{}-{}", config.name, config.input.stem().string());
}

std::filesystem::path default_run_folder(const SweepConfig& config) {
  return std::filesystem::path("medax-runs") / config.name;
}

bool check_pipeline_file(const std::filesystem::path& pipeline) {
  std::error_code ec;
  if (!std::filesystem::is_directory(pipeline, ec)) return true;  // a missing file is reported by the loader
  fmt::print(stderr, "{}: error: is a folder, not a pipeline file; give a pipeline YAML file "
             "(e.g. pipelines/quickstart.yaml)\n", pipeline.string());
  return false;
}

int list_plugins() {
  Registry& registry = Registry::global();
  std::vector<std::vector<std::string>> rows{{"ROLE", "NAME", "PACKAGE", "VERSION", "SUMMARY"}};
  for (const RegisteredStage* s : registry.stages())
    rows.push_back({std::string(to_string(s->info().role)), s->info().name, s->package->name, s->package->version,
                    s->info().summary});
  if (rows.size() == 1) {
    fmt::print("no stages found; plugin folders searched:\n");
    for (const auto& dir : Registry::search_path()) fmt::print("  {}\n", dir.string());
  } else {
    print_table(rows);
  }
  print_load_errors(registry);
  return registry.errors().empty() ? 0 : 2;
}

int describe(const std::string& name, bool markdown) {
  Registry& registry = Registry::global();
  const RegisteredStage* s = registry.find(name);
  if (!s) {
    std::string hint;
    for (const std::string& n : registry.suggest(name)) hint += (hint.empty() ? " (did you mean " : ", ") + n;
    fmt::print(stderr, "error: no stage named '{}'{}; `medax plugins` lists them\n", name,
               hint.empty() ? "" : hint + "?)");
    return 2;
  }
  const StageInfo& info = s->info();
  if (markdown) {
    fmt::print("{}", param_block_markdown(info));
    return 0;
  }
  fmt::print("{} ({} stage, package {} {})\n  {}\n", info.name, to_string(info.role), s->package->name,
             s->package->version, info.summary);
  if (!info.doc.empty()) fmt::print("  docs: {}\n", info.doc);
  if (info.params.empty()) {
    fmt::print("\nno parameters\n");
    return 0;
  }
  fmt::print("\n");
  std::vector<std::vector<std::string>> rows{{"PARAMETER", "TYPE", "DEFAULT", "RANGE", "UNIT", "DOC"}};
  for (const ParamSpec& p : info.params)
    rows.push_back({p.name, std::string(to_string(p.type)), p.default_text(), p.range_text(), p.unit, p.doc});
  print_table(rows);
  return 0;
}

int validate(const RunArgs& args) {
  if (!check_pipeline_file(args.pipeline)) return 2;
  if (is_sweep(args.pipeline)) return validate_sweep(args);
  Registry& registry = Registry::global();
  auto config = load(args, registry);
  if (!config) return 2;
  fmt::print("{}: valid ({} stages: ", args.pipeline.string(), config->stages.size());
  for (std::size_t i = 0; i < config->stages.size(); ++i)
    fmt::print("{}{}", i ? " -> " : "", config->stages[i].id);
  fmt::print(")\n");
  return 0;
}

int run(const RunArgs& args) {
  if (!check_pipeline_file(args.pipeline)) return 2;
  if (!args.single_job && is_sweep(args.pipeline)) return run_sweep(args);
  if (!args.single_job && args.backend != "local") {
    fmt::print(stderr,
               "error: --backend {} runs the jobs of an experiment (a file with `sweep:` or `inputs:`); {} is one "
               "pipeline: drop --backend, or write an experiment around it (docs/experiments.md)\n",
               args.backend, args.pipeline.string());
    return 2;
  }
  Registry& registry = Registry::global();
  auto config = load(args, registry);
  if (!config) return 2;
  RunOptions options;
  options.out_dir = args.out.empty() ? default_run_folder(*config) : args.out;
  options.quiet = args.quiet;
  const RunResult result = run_pipeline(*config, options);
  if (!result.wrote_log) {  // nothing ran, there is no log
    fmt::print(stderr, "error: {}\n", result.error);
    return 1;
  }
  if (!result.ok) {
    fmt::print(stderr, "error: {}\n(see {}/log.txt)\n", result.error, result.out_dir.string());
    return failed_run_exit_code(result.signal);
  }
  fmt::print("results: {}\n", std::filesystem::absolute(result.out_dir).lexically_normal().string());
  return 0;
}

}  // namespace medax::cli
