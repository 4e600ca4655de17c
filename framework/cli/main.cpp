// medax: run, validate and inspect medial-axis pipelines.
#include "commands.hpp"
#include "view_command.hpp"

#include <medax/kernel/registry.hpp>
#include <medax/version.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <csignal>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

namespace {

/// One warning per plugin file that failed to load, in every command but `plugins` (which lists
/// them as errors) and sweep jobs (their controller warned): a pipeline that does not need the
/// file still runs with its usual exit code.
void warn_broken_plugins() {
  for (const std::string& line : medax::Registry::global().errors()) fmt::print(stderr, "warning: {}\n", line);
}

/// The pipeline file, --input and --set, as `validate`, `run` and `bench` take them.
void add_pipeline_options(CLI::App* cmd, std::filesystem::path& pipeline, std::filesystem::path& input,
                          std::vector<std::string>& settings) {
  cmd->add_option("PIPELINE", pipeline, "Pipeline YAML file")->required();
  cmd->add_option("--input,-i", input, "Input mesh (replaces the pipeline's `input:`)");
  cmd->add_option("--set,-s", settings, "Override a parameter: STAGE.PARAM=VALUE (STAGE is the stage id)");
}

/// Every subcommand and the arguments CLI11 parses into.
struct Commands {
  CLI::App* plugins = nullptr;
  CLI::App* describe = nullptr;
  CLI::App* validate = nullptr;
  CLI::App* run = nullptr;
  CLI::App* bench = nullptr;
  CLI::App* view = nullptr;
  CLI::App* snapshot = nullptr;
  std::string describe_name;
  bool describe_markdown = false;
  medax::cli::RunArgs run_args;
  bool view_after_run = false;
  medax::cli::BenchArgs bench_args;
  medax::cli::ViewArgs view_args;
  medax::cli::SnapshotArgs snapshot_args;
};

void add_commands(CLI::App& app, Commands& c) {
  c.plugins = app.add_subcommand("plugins", "List every stage: role, name, package, version, summary");

  c.describe = app.add_subcommand("describe", "Print a stage's parameters");
  c.describe->add_option("NAME", c.describe_name, "Stage name (see `medax plugins`)")->required();
  c.describe->add_flag("--markdown", c.describe_markdown, "Print the parameter block of the stage's docs page");

  medax::cli::RunArgs& args = c.run_args;
  c.validate = app.add_subcommand("validate", "Check a pipeline without running it");
  add_pipeline_options(c.validate, args.pipeline, args.input, args.settings);
  c.run = app.add_subcommand("run", "Run a pipeline into a run folder");
  add_pipeline_options(c.run, args.pipeline, args.input, args.settings);
  medax::cli::add_run_options(*c.run, args);
  c.run->add_flag("--view", c.view_after_run,
                  "When the run ends, write its viewer page (an experiment: results.html) and open it (`medax view`)");

  medax::cli::BenchArgs& bench = c.bench_args;
  c.bench = app.add_subcommand("bench", "Time a pipeline: warm-up runs, then min and median per stage");
  add_pipeline_options(c.bench, bench.pipeline, bench.input, bench.settings);
  c.bench->add_option("--warmup", bench.warmup, "Untimed runs first")->check(CLI::NonNegativeNumber);
  c.bench->add_option("--repeat", bench.repeat, "Timed runs")->check(CLI::PositiveNumber);

  c.view = medax::cli::add_view_command(app, c.view_args);
  c.snapshot = medax::cli::add_snapshot_command(app, c.snapshot_args);
}

/// Runs the parsed subcommand; its exit code.
int dispatch(const Commands& c) {
  if (!c.plugins->parsed() && !c.run_args.single_job) warn_broken_plugins();
  if (c.plugins->parsed()) return medax::cli::list_plugins();
  if (c.describe->parsed()) return medax::cli::describe(c.describe_name, c.describe_markdown);
  if (c.validate->parsed()) return medax::cli::validate(c.run_args);
  if (c.bench->parsed()) return medax::cli::bench(c.bench_args);
  if (c.view->parsed()) return medax::cli::view(c.view_args);
  if (c.snapshot->parsed()) return medax::cli::snapshot(c.snapshot_args);
  const int code = medax::cli::run(c.run_args);
  return code == 0 && c.view_after_run ? medax::cli::view_finished_run(c.run_args) : code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"medax: compute, simplify, structure and evaluate 3D medial axes"};
  app.set_version_flag("--version", std::string(medax::kVersion));
  app.require_subcommand(1);
  Commands commands;
  add_commands(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    fmt::print(stderr, "error: {}\nRun with --help for more information.\n", e.what());
    return 2;  // usage errors exit 2, not CLI11's own codes
  }
  // Over a file-size limit (ulimit -f) a write fails with EFBIG and is reported like a full
  // disk, instead of SIGXFSZ killing medax mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
  // The last catch: whatever escapes a command is reported, never `terminate`.
  try {
    return dispatch(commands);
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "error: out of memory (std::bad_alloc); try a smaller input or raise the memory limit\n");
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
  } catch (...) {
    fmt::print(stderr, "error: an unknown exception stopped medax\n");
  }
  return 1;
}
