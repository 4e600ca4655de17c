// `medax snapshot`: the viewer page rendered to a PNG by headless Chromium.
#include "snapshot_page.hpp"
#include "view_command.hpp"
#include "view_page.hpp"
#include "view_scene.hpp"

#include <medax/io.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

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
  if (!(in >> s.width >> x >> s.height) || x != 'x' || !in.eof() || s.width < 16 || s.height < 16 || s.width > 8192 ||
      s.height > 8192)
    return std::nullopt;
  return s;
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
  shot->add_option("--timeout", args.timeout, "Seconds before the browser is killed")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  return shot;
}

int snapshot(const SnapshotArgs& args) {
  const Size size = *parse_size(args.size);  // checked when parsed
  const ViewScene scene = read_view_scene(args.run_folder);
  if (!check_field(scene, args.scene.field)) return 2;
  for (const std::string& note : scene.notes) fmt::print(stderr, "note: {}\n", note);
  const ScratchFolder scratch;
  const fs::path page = scratch.path() / "view.html";
  const std::string html = viewer_page(scene);
  write_file_atomic(page, [&html](std::ostream& out) { out << html; });
  take_picture(page, args.scene, size.width, size.height, args.out, args.timeout, scratch.path());
  fmt::print("snapshot: {} ({}x{})\n", fs::absolute(args.out).lexically_normal().string(), size.width, size.height);
  return 0;
}

}  // namespace medax::cli
