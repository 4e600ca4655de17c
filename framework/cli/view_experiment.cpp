#include "view_experiment.hpp"

#include "snapshot_page.hpp"
#include "view_assets.hpp"
#include "view_page.hpp"
#include "view_scene.hpp"

#include <medax/io.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace medax::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kPictureWidth = 320, kPictureHeight = 240;  // shown at half size: sharp on high-DPI screens

std::string data_uri(const fs::path& png) {
  return "data:image/png;base64," + base64(read_text(png).data(), fs::file_size(png));
}

/// The job's viewer page and, when asked and possible, its picture; {} when the job has no medial file.
nlohmann::json job_entry(const fs::path& experiment, const std::string& job, bool& pictures,
                         const ScratchFolder& scratch) {
  const fs::path folder = experiment / "jobs" / job;
  if (!fs::exists(folder / "medial.ply") && !fs::exists(folder / "medial.ma")) return nullptr;
  fs::create_directories(experiment / "viewers");
  const fs::path page = experiment / "viewers" / (job + ".html");
  const std::string html = viewer_page(read_view_scene(folder));
  write_file_atomic(page, [&html](std::ostream& out) { out << html; });
  nlohmann::json entry{{"viewer", "viewers/" + job + ".html"}, {"thumbnail", ""}};
  if (!pictures) return entry;
  try {
    const fs::path png = scratch.path() / "picture.png";
    take_picture(page, SceneSettings{"iso", "", "", 1, -1, false}, kPictureWidth, kPictureHeight, png, 60,
                 scratch.path());
    entry["thumbnail"] = data_uri(png);
  } catch (const std::exception& e) {
    fmt::print(stderr, "note: no pictures in results.html: {}\n", e.what());
    pictures = false;  // the same reason would stop every other job's picture
  }
  return entry;
}

nlohmann::json plot_entries(const fs::path& experiment) {
  nlohmann::json plots = nlohmann::json::array();
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(experiment / "plots", ec))
    if (entry.path().extension() == ".png") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& png : files) plots.push_back({{"name", png.stem().string()}, {"src", data_uri(png)}});
  return plots;
}

}  // namespace

fs::path write_results_page(const fs::path& experiment, bool pictures) {
  const auto rows = read_csv(experiment / "results.csv");
  if (rows.empty() || rows[0].empty() || rows[0][0] != "job")
    throw std::runtime_error(fmt::format("{} does not start with a 'job' column: is it a medax results table?",
                                         (experiment / "results.csv").string()));
  const ScratchFolder scratch;
  nlohmann::json jobs = nlohmann::json::object();
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const nlohmann::json entry = job_entry(experiment, rows[r][0], pictures, scratch);
    if (!entry.is_null()) jobs[rows[r][0]] = entry;
  }
  const fs::path folder = fs::absolute(experiment).lexically_normal();
  const std::string title = (folder.filename().empty() ? folder.parent_path() : folder).filename().string();
  const nlohmann::json data{{"title", title},
                            {"columns", rows[0]},
                            {"rows", std::vector<std::vector<std::string>>(rows.begin() + 1, rows.end())},
                            {"jobs", jobs},
                            {"plots", plot_entries(experiment)}};
  const std::string html =
      fill_template(viewer_assets::kResultsHtml, {{"title", html_escaped(title)}, {"data", script_safe(data.dump())}});
  const fs::path page = experiment / "results.html";
  write_file_atomic(page, [&html](std::ostream& out) { out << html; });
  return page;
}

}  // namespace medax::cli
