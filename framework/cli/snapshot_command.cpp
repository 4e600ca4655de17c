// `medax snapshot`: the viewer page rendered to a PNG by headless Chromium.
#include "snapshot_chromium.hpp"
#include "view_command.hpp"
#include "view_page.hpp"
#include "view_scene.hpp"

#include <medax/io.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace medax::cli {

namespace fs = std::filesystem;

namespace {

struct Size {
  int width = 0, height = 0;
};

/// WIDTHxHEIGHT, or nothing when `text` is not one.
std::optional<Size> parse_size(const std::string& text) {
  Size s;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> s.width >> x >> s.height) || x != 'x' || !in.eof() || s.width < 16 || s.height < 16 ||
      s.width > 8192 || s.height > 8192)
    return std::nullopt;
  return s;
}

/// The page's URL query for `settings` at `size` (framework/viewer/viewer.js reads it).
std::string page_query(const SceneSettings& settings, Size size) {
  std::string q = fmt::format("?w={}&h={}&ui=0&view={}&zoom={}", size.width, size.height, settings.view, settings.zoom);
  if (!settings.field.empty()) q += "&field=" + settings.field;
  if (!settings.layers.empty()) q += "&layers=" + settings.layers;
  if (settings.pick >= 0) q += fmt::format("&pick={}", settings.pick);
  if (!settings.legend) q += "&legend=0";
  return q;
}

/// False (after saying which fields there are) when `field` names none of the scene's fields.
bool check_field(const ViewScene& scene, const std::string& field) {
  if (field.empty() || field == "none") return true;
  std::string known;
  for (const ViewField& f : scene.fields) {
    if (field == f.name || field == f.element + ":" + f.name) return true;
    known += (known.empty() ? "" : ", ") + f.element + ":" + f.name;
  }
  fmt::print(stderr, "error: --field: this run has no field '{}'; its fields: {} (or none)\n", field, known);
  return false;
}

/// A fresh temporary folder for the page, the browser's profile and its log, removed at the end.
struct ScratchFolder {
  fs::path path;
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "medax-snapshot-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error(fmt::format("cannot create a temporary folder {}: {}", pattern, std::strerror(errno)));
    path = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
};

void take_picture(const fs::path& page, const SnapshotArgs& args, Size size, const fs::path& scratch) {
  const fs::path browser = find_chromium();
  const fs::path png = fs::absolute(args.out);
  fs::remove(png);
  std::vector<std::string> flags = headless_flags(scratch / "profile", size.width, size.height);
  flags.push_back("--screenshot=" + png.string());
  flags.push_back("file://" + fs::absolute(page).string() + page_query(args.scene, size));
  const BrowserRun run = run_browser(browser, flags, scratch / "browser.log", args.timeout);
  const std::vector<std::string> errors = page_errors(run.log);
  if (!errors.empty()) throw std::runtime_error(fmt::format("the viewer page reported: {}", errors.front()));
  if (run.timed_out)
    throw std::runtime_error(fmt::format("{} took more than {} s; raise --timeout for a large run", browser.string(), args.timeout));
  if (run.exit_code != 0 || !fs::exists(png)) {
    const std::string tail = run.log.substr(run.log.size() > 1500 ? run.log.size() - 1500 : 0);
    throw std::runtime_error(fmt::format("{} wrote no picture (exit code {}); its last words:\n{}", browser.string(),
                                         run.exit_code, tail));
  }
}

}  // namespace

CLI::App* add_snapshot_command(CLI::App& app, SnapshotArgs& args) {
  auto* shot = app.add_subcommand("snapshot", "Render a run folder's viewer to a PNG (headless Chromium)");
  shot->add_option("RUN_FOLDER", args.run_folder, "A run folder")->required();
  shot->add_option("--out,-o", args.out, "The PNG to write")->required();
  shot->add_option("--size", args.size, "WIDTHxHEIGHT in pixels")
      ->check([](const std::string& text) {
        return parse_size(text) ? std::string() : "'" + text + "' is not WIDTHxHEIGHT in pixels (16 to 8192)";
      })
      ->capture_default_str();
  shot->add_option("--view", args.scene.view, "Camera: iso, front, back, left, right, top or bottom")
      ->check(CLI::IsMember({"iso", "front", "back", "left", "right", "top", "bottom"}))
      ->capture_default_str();
  shot->add_option("--field", args.scene.field,
                   "Colour by this field (NAME or vertex:NAME, face:NAME, edge:NAME; none: plain; default radius)");
  shot->add_option("--layers", args.scene.layers,
                   "Layers shown, comma-separated: surface, triangles, curves, vertices, spheres, reconstruction, "
                   "or a file of the run (default: the viewer's)");
  shot->add_option("--zoom", args.scene.zoom, "Closer (> 1) or farther (< 1)")->check(CLI::PositiveNumber);
  shot->add_option("--pick", args.scene.pick, "Show the sphere of this medial vertex")->check(CLI::NonNegativeNumber);
  shot->add_flag("!--no-legend", args.scene.legend, "No colour legend");
  shot->add_option("--timeout", args.timeout, "Seconds before the browser is killed")->check(CLI::PositiveNumber)
      ->capture_default_str();
  return shot;
}

int snapshot(const SnapshotArgs& args) {
  const Size size = *parse_size(args.size);  // checked when parsed
  const ViewScene scene = read_view_scene(args.run_folder);
  if (!check_field(scene, args.scene.field)) return 2;
  for (const std::string& note : scene.notes) fmt::print(stderr, "note: {}\n", note);
  const ScratchFolder scratch;
  const fs::path page = scratch.path / "view.html";
  const std::string html = viewer_page(scene);
  write_file_atomic(page, [&html](std::ostream& out) { out << html; });
  take_picture(page, args, size, scratch.path);
  fmt::print("snapshot: {} ({}x{})\n", fs::absolute(args.out).lexically_normal().string(), size.width, size.height);
  return 0;
}

}  // namespace medax::cli
