#include "view_command.hpp"

#include "view_experiment.hpp"
#include "view_page.hpp"
#include "view_scene.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/sweep.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>

extern char** environ;

namespace medax::cli {

namespace fs = std::filesystem;

namespace {

fs::path default_page(const fs::path& run_folder) {
  fs::path folder = fs::absolute(run_folder).lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();
  return folder.parent_path() / (folder.filename().string() + ".html");
}

/// Opens `page` with xdg-open when there is a display; true when it did.
bool open_in_browser(const fs::path& page) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return false;
  std::string opener = "xdg-open", target = page.string();
  char* argv[] = {opener.data(), target.data(), nullptr};
  pid_t pid = 0;
  if (::posix_spawnp(&pid, argv[0], nullptr, nullptr, argv, environ) != 0) return false;
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// Writes the page of `run_folder` to `out` (default beside the folder); prints what it left out.
fs::path write_page(const fs::path& run_folder, const fs::path& out) {
  const ViewScene scene = read_view_scene(run_folder);
  for (const std::string& note : scene.notes) fmt::print(stderr, "note: {}\n", note);
  const fs::path page = out.empty() ? default_page(run_folder) : out;
  const std::string html = viewer_page(scene);
  write_file_atomic(page, [&html](std::ostream& stream) { stream << html; });
  return page;
}

void announce(const char* what, const fs::path& page, bool open) {
  fmt::print("{}: {}\n", what, fs::absolute(page).lexically_normal().string());
  if (open && !open_in_browser(page)) fmt::print("open it in a web browser (no display to open it here)\n");
}

int show(const fs::path& run_folder, const fs::path& out, bool open) {
  announce("viewer", write_page(run_folder, out), open);
  return 0;
}

}  // namespace

CLI::App* add_view_command(CLI::App& app, ViewArgs& args) {
  auto* view = app.add_subcommand("view", "Write a run folder as one self-contained HTML page (3D viewer)");
  view->add_option("RUN_FOLDER", args.run_folder,
                   "A run folder (what `medax run` printed after 'results:'), or an experiment's folder: then its "
                   "results.html (table, plots, a picture and a viewer page per job)")
      ->required();
  view->add_option("--out,-o", args.out, "The page (default: <RUN_FOLDER>.html beside the folder)");
  view->add_flag("--no-open", args.no_open, "Only print the page's path; do not open a browser");
  view->add_flag("--no-pictures", args.no_pictures, "Experiments: no picture of each job in results.html");
  return view;
}

int view(const ViewArgs& args) {
  if (!is_experiment_folder(args.run_folder)) return show(args.run_folder, args.out, !args.no_open);
  if (!args.out.empty()) {
    fmt::print(stderr, "error: --out: {} is an experiment: its page is always its results.html\n",
               args.run_folder.string());
    return 2;
  }
  announce("results", write_results_page(args.run_folder, !args.no_pictures), !args.no_open);
  return 0;
}

int view_finished_run(const RunArgs& args) {
  fs::path folder = args.out;
  if (folder.empty() && is_sweep(args.pipeline)) {
    folder = default_run_folder(load_sweep(args.pipeline));
  } else if (folder.empty()) {
    folder = default_run_folder(load_pipeline(args.pipeline, Registry::global(), Overrides{args.input, args.settings}));
  }
  return view(ViewArgs{folder, {}, false, false});
}

}  // namespace medax::cli
