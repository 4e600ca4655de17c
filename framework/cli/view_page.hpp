#pragma once
// The viewer page: the template, three.js and the scene's data in one HTML file.
#include "view_scene.hpp"

#include <filesystem>
#include <string>

namespace medax::cli {

/// The folder holding three.min.js and examples/js/controls/OrbitControls.js: $MEDAX_THREE_DIR,
/// else where CMake found Debian's libjs-three. Throws saying how to install it when absent.
std::filesystem::path three_js_dir();

/// The self-contained page showing `scene`.
std::string viewer_page(const ViewScene& scene);

}  // namespace medax::cli
