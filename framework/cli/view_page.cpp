#include "view_page.hpp"

#include "view_assets.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace medax::cli {

namespace fs = std::filesystem;

namespace {

const char* const kThreeFile = "three.min.js";
const char* const kOrbitFile = "examples/js/controls/OrbitControls.js";

/// A typed array's bytes in base64 (the page decodes it into the same typed array).
template <class T>
std::string typed_array(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

nlohmann::json scene_json(const ViewScene& scene) {
  nlohmann::json fields = nlohmann::json::array();
  for (const ViewField& f : scene.fields)
    fields.push_back({{"name", f.name}, {"element", f.element}, {"label", f.label}, {"values", typed_array(f.values)}});
  nlohmann::json surfaces = nlohmann::json::array();
  for (const ViewSurface& s : scene.surfaces)
    surfaces.push_back({{"id", s.id},
                        {"name", s.name},
                        {"positions", typed_array(s.positions)},
                        {"triangles", typed_array(s.triangles)},
                        {"colors", s.colours.empty() ? "" : typed_array(s.colours)},
                        {"color", s.colour},
                        {"opacity", s.opacity},
                        {"visible", s.visible},
                        {"field", s.field.name.empty() ? nlohmann::json(nullptr)
                                                       : nlohmann::json{{"name", s.field.name},
                                                                        {"element", s.field.element},
                                                                        {"label", s.field.label},
                                                                        {"values", typed_array(s.field.values)}}}});
  return {{"title", scene.title},
          {"medial",
           {{"positions", typed_array(scene.positions)},
            {"radii", typed_array(scene.radii)},
            {"triangles", typed_array(scene.triangles)},
            {"curves", typed_array(scene.curves)},
            {"fields", fields}}},
          {"surfaces", surfaces}};
}

}  // namespace

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", file.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string base64(const void* data, std::size_t size) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const unsigned chunk = bytes[i] << 16 | (i + 1 < size ? bytes[i + 1] << 8 : 0) | (i + 2 < size ? bytes[i + 2] : 0);
    for (std::size_t k = 0; k < 4; ++k) out += i + k <= size ? kDigits[(chunk >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string script_safe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.insert(at + 1, "\\");
  return text;
}

std::string html_escaped(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

std::string fill_template(std::string_view page, const std::map<std::string, std::string>& slots) {
  std::string out;
  const std::string_view open = "<!--medax:", close = "-->";
  for (std::size_t at = 0;;) {
    const std::size_t slot = page.find(open, at);
    if (slot == std::string_view::npos) return out.append(page.substr(at));
    const std::size_t end = page.find(close, slot);
    const std::string name(page.substr(slot + open.size(), end - slot - open.size()));
    out.append(page.substr(at, slot - at)).append(slots.at(name));
    at = end + close.size();
  }
}

fs::path three_js_dir() {
  const char* env = std::getenv("MEDAX_THREE_DIR");
  const fs::path dir = env && *env ? fs::path(env) : fs::path(MEDAX_THREE_DIR);
  for (const char* file : {kThreeFile, kOrbitFile})
    if (!fs::is_regular_file(dir / file))
      throw std::runtime_error(
          fmt::format("the viewer needs three.js and {} is not there; install Debian's libjs-three (apt-get install "
                      "libjs-three) or set MEDAX_THREE_DIR to a folder holding {} and {}",
                      (dir / file).string(), kThreeFile, kOrbitFile));
  return dir;
}

std::string viewer_page(const ViewScene& scene) {
  const fs::path three = three_js_dir();
  return fill_template(viewer_assets::kHtml, {{"title", html_escaped(scene.title)},
                                              {"css", std::string(viewer_assets::kCss)},
                                              {"three", read_text(three / kThreeFile)},
                                              {"orbit", read_text(three / kOrbitFile)},
                                              {"data", script_safe(scene_json(scene).dump())},
                                              {"js", std::string(viewer_assets::kJs)}});
}

}  // namespace medax::cli
