#pragma once
// An experiment's results.html (beside its results.md): the results table (sortable), its plots,
// and a picture of each job linking to the job's viewer page (viewers/<job>.html).
#include "view_csv.hpp"

#include <filesystem>

namespace medax::cli {

/// Writes <experiment>/results.html and a viewer page per job into <experiment>/viewers/ (with a
/// picture of it when `pictures` and Chromium is there); returns the results page.
std::filesystem::path write_results_page(const std::filesystem::path& experiment, bool pictures);

}  // namespace medax::cli
