#pragma once
// The viewer page: the template, three.js and the scene's data in one HTML file.
#include "view_scene.hpp"

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace medax::cli {

/// The folder holding three.min.js and examples/js/controls/OrbitControls.js: $MEDAX_THREE_DIR,
/// else where CMake found Debian's libjs-three. Throws saying how to install it when absent.
std::filesystem::path three_js_dir();

/// The whole file; throws naming it when it cannot be read.
std::string read_text(const std::filesystem::path& file);
/// `size` bytes in base64.
std::string base64(const void* bytes, std::size_t size);
/// JSON text safe inside a <script> element ("</" would close it).
std::string script_safe(std::string json);
std::string html_escaped(const std::string& text);
/// `page` with each <!--medax:NAME--> slot replaced by slots.at(NAME).
std::string fill_template(std::string_view page, const std::map<std::string, std::string>& slots);

/// The self-contained page showing `scene`.
std::string viewer_page(const ViewScene& scene);

}  // namespace medax::cli
