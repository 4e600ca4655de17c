#include "view_command.hpp"

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

int show(const fs::path& run_folder, const fs::path& out, bool open) {
  const fs::path page = write_page(run_folder, out);
  fmt::print("viewer: {}\n", fs::absolute(page).lexically_normal().string());
  if (open && !open_in_browser(page)) fmt::print("open it in a web browser (no display to open it here)\n");
  return 0;
}

}  // namespace

CLI::App* add_view_command(CLI::App& app, ViewArgs& args) {
  auto* view = app.add_subcommand("view", "Write a run folder as one self-contained HTML page (3D viewer)");
  view->add_option("RUN_FOLDER", args.run_folder, "A run folder (what `medax run` printed after 'results:')")
      ->required();
  view->add_option("--out,-o", args.out, "The page (default: <RUN_FOLDER>.html beside the folder)");
  view->add_flag("--no-open", args.no_open, "Only print the page's path; do not open a browser");
  return view;
}

int view(const ViewArgs& args) { return show(args.run_folder, args.out, !args.no_open); }

int view_finished_run(const RunArgs& args) {
  if (is_sweep(args.pipeline)) {
    fmt::print("--view shows one run: view a job of the experiment with `medax view <job folder>`\n");
    return 0;
  }
  fs::path folder = args.out;
  if (folder.empty()) {  // the folder `run` chose: medax-runs/<pipeline>-<input stem>
    const PipelineConfig config = load_pipeline(args.pipeline, Registry::global(), Overrides{args.input, args.settings});
    folder = fmt::format("medax-runs/{}-{}", config.name, config.input.stem().string());
  }
  return show(folder, {}, true);
}

}  // namespace medax::cli
