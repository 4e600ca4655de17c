// medax: run, validate and inspect medial-axis pipelines.
#include "commands.hpp"
#include "view_command.hpp"

#include <medax/kernel/registry.hpp>
#include <medax/version.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <csignal>
#include <exception>
#include <new>

namespace {

/// One warning per plugin file that failed to load, in every command but `plugins` (which lists
/// them as errors) and sweep jobs (their controller warned): a pipeline that does not need the
/// file still runs with its usual exit code.
void warn_broken_plugins() {
  for (const std::string& line : medax::Registry::global().errors()) fmt::print(stderr, "warning: {}\n", line);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"medax: compute, simplify, structure and evaluate 3D medial axes"};
  app.set_version_flag("--version", std::string(medax::kVersion));
  app.require_subcommand(1);

  auto* plugins = app.add_subcommand("plugins", "List every stage: role, name, package, version, summary");

  std::string name;
  auto* describe = app.add_subcommand("describe", "Print a stage's parameters");
  describe->add_option("NAME", name, "Stage name (see `medax plugins`)")->required();
  bool markdown = false;
  describe->add_flag("--markdown", markdown, "Print the parameter block of the stage's docs page");

  medax::cli::RunArgs args;
  const auto add_pipeline_options = [&](CLI::App* cmd) {
    cmd->add_option("PIPELINE", args.pipeline, "Pipeline YAML file")->required();
    cmd->add_option("--input,-i", args.input, "Input mesh (replaces the pipeline's `input:`)");
    cmd->add_option("--set,-s", args.settings, "Override a parameter: STAGE.PARAM=VALUE (STAGE is the stage id)");
  };
  auto* validate = app.add_subcommand("validate", "Check a pipeline without running it");
  add_pipeline_options(validate);
  auto* run = app.add_subcommand("run", "Run a pipeline into a run folder");
  add_pipeline_options(run);
  medax::cli::add_run_options(*run, args);
  bool view_after_run = false;
  run->add_flag("--view", view_after_run,
                "When the run ends, write its viewer page (an experiment: results.html) and open it (`medax view`)");

  medax::cli::BenchArgs bench_args;
  auto* bench = app.add_subcommand("bench", "Time a pipeline: warm-up runs, then min and median per stage");
  bench->add_option("PIPELINE", bench_args.pipeline, "Pipeline YAML file")->required();
  bench->add_option("--input,-i", bench_args.input, "Input mesh (replaces the pipeline's `input:`)");
  bench->add_option("--set,-s", bench_args.settings, "Override a parameter: STAGE.PARAM=VALUE");
  bench->add_option("--warmup", bench_args.warmup, "Untimed runs first")->check(CLI::NonNegativeNumber);
  bench->add_option("--repeat", bench_args.repeat, "Timed runs")->check(CLI::PositiveNumber);

  medax::cli::ViewArgs view_args;
  auto* view = medax::cli::add_view_command(app, view_args);
  medax::cli::SnapshotArgs snapshot_args;
  auto* snapshot = medax::cli::add_snapshot_command(app, snapshot_args);

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
    if (!plugins->parsed() && !args.single_job) warn_broken_plugins();
    if (plugins->parsed()) return medax::cli::list_plugins();
    if (describe->parsed()) return medax::cli::describe(name, markdown);
    if (validate->parsed()) return medax::cli::validate(args);
    if (bench->parsed()) return medax::cli::bench(bench_args);
    if (view->parsed()) return medax::cli::view(view_args);
    if (snapshot->parsed()) return medax::cli::snapshot(snapshot_args);
    const int code = medax::cli::run(args);
    return code == 0 && view_after_run ? medax::cli::view_finished_run(args) : code;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "error: out of memory (std::bad_alloc); try a smaller input or raise the memory limit\n");
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
  } catch (...) {
    fmt::print(stderr, "error: an unknown exception stopped medax\n");
  }
  return 1;
}
