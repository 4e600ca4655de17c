#pragma once
// The viewer page's own files (framework/viewer), compiled into medax by framework/CMakeLists.txt
// (view_assets.cpp is generated), so that `medax view` needs no installed template.
#include <string_view>

namespace medax::cli::viewer_assets {

extern const std::string_view kHtml;         ///< viewer.html, with <!--medax:NAME--> slots
extern const std::string_view kCss;          ///< viewer.css
extern const std::string_view kJs;           ///< viewer.js
extern const std::string_view kResultsHtml;  ///< results.html (an experiment's page), <!--medax:NAME--> slots

}  // namespace medax::cli::viewer_assets
