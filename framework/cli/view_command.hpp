#pragma once
// `medax view` (a run folder as one self-contained HTML page), `medax snapshot` (that page as a
// PNG, by headless Chromium) and `medax run --view`. See docs/viewer.md.
#include "commands.hpp"

#include <filesystem>
#include <string>

namespace CLI {
class App;
}

namespace medax::cli {

struct ViewArgs {
  std::filesystem::path run_folder;
  std::filesystem::path out;  ///< default: <run folder>.html beside the folder
  bool no_open = false;       ///< only print the page's path
  bool no_pictures = false;   ///< an experiment's results.html without a picture per job
};

/// What the page shows; the same settings as the page's URL query (framework/viewer/viewer.js).
struct SceneSettings {
  std::string view = "iso";
  std::string field;   ///< empty: radius
  std::string layers;  ///< comma-separated layer ids; empty: the page's defaults
  double zoom = 1;
  long pick = -1;  ///< a medial vertex whose sphere is shown
  bool legend = true;
};

struct SnapshotArgs {
  std::filesystem::path run_folder;
  std::filesystem::path out;
  std::string size = "1200x900";
  SceneSettings scene;
  double timeout = 60;  ///< seconds before the browser is killed
};

CLI::App* add_view_command(CLI::App& app, ViewArgs& args);
CLI::App* add_snapshot_command(CLI::App& app, SnapshotArgs& args);

int view(const ViewArgs& args);
int snapshot(const SnapshotArgs& args);
/// `medax run --view`: the page of the run `args` just made, opened where there is a display.
int view_finished_run(const RunArgs& args);

}  // namespace medax::cli
