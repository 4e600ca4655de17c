#pragma once
// The viewer tests' fixture: one small real run (quickstart's axis of the bundled ellipsoid),
// its viewer page, and headless Chromium driven the way `medax snapshot` drives it.
#include "png_pixels.hpp"
#include "snapshot_chromium.hpp"

#include <catch2/catch.hpp>
#include <command_output.hpp>
#include <test_paths.hpp>

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace medax::test {

/// A scratch name of this process: ctest runs each test case as its own process, two at a time,
/// and cases that shared one folder removed each other's run and browser profile.
inline std::string per_process(const std::string& name) { return name + "-" + std::to_string(::getpid()); }

inline std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `medax ARGS` (the built binary, its own plugins), capturing stdout and stderr. No display:
/// `view` prints the page's path instead of opening a browser.
inline CommandOutput run_medax(const std::string& args) {
  return run_command("env -u DISPLAY -u WAYLAND_DISPLAY MEDAX_PLUGIN_PATH= '" + std::string(MEDAX_CLI) + "' " + args,
                     binary_dir() / "tests" / "scratch" / (per_process("viewer_medax") + ".stderr.txt"));
}

/// The run folder of tests/viewer/small_run.yaml (quickstart's axis of tests/data/ellipsoid.off),
/// made once per process.
inline const std::filesystem::path& small_run() {
  static const std::filesystem::path folder = [] {
    const auto dir = scratch_dir(per_process("viewer_run")) / "quickstart-ellipsoid";
    const auto r = run_medax("run '" + (source_dir() / "tests" / "viewer" / "small_run.yaml").string() + "' --input '" +
                             (data_dir() / "ellipsoid.off").string() + "' --out '" + dir.string() + "' --quiet");
    INFO(r.out << r.err);
    REQUIRE(r.code == 0);
    return dir;
  }();
  return folder;
}

/// `medax view` of the small run into `page`.
inline std::filesystem::path small_run_page() {
  const auto page = small_run().parent_path() / "view.html";
  const auto r = run_medax("view '" + small_run().string() + "' --no-open -o '" + page.string() + "'");
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  return page;
}

/// Headless Chromium on a page; a browser that cannot start fails the test with its last words.
class Browser {
 public:
  Browser() : dir_(scratch_dir(per_process("viewer_browser"))) {}
  ~Browser() {
    std::error_code ignored;  // the profile is megabytes and per process: do not let them pile up
    std::filesystem::remove_all(dir_, ignored);
  }
  Browser(const Browser&) = delete;
  Browser& operator=(const Browser&) = delete;

  /// The page's DOM after its scripts ran (`--dump-dom`), and the browser's log in `log`.
  std::string dom(const std::filesystem::path& page, const std::string& query, std::string& log) {
    auto flags = medax::cli::headless_flags(dir_ / "profile", 800, 600);
    flags.push_back("--dump-dom");
    flags.push_back(url(page, query));
    const auto run = launch(flags);
    log = run.log;
    return run.log;  // the DOM is printed on stdout, which run_browser merges into the log
  }

  /// A `width` x `height` screenshot of the page with `query`.
  Picture screenshot(const std::filesystem::path& page, const std::string& query, int width, int height) {
    const auto png = dir_ / ("shot" + std::to_string(++shots_) + ".png");
    auto flags = medax::cli::headless_flags(dir_ / "profile", width, height);
    flags.push_back("--screenshot=" + png.string());
    flags.push_back(url(page, query + "&w=" + std::to_string(width) + "&h=" + std::to_string(height) + "&ui=0"));
    launch(flags);
    return read_png(png);
  }

 private:
  static std::string url(const std::filesystem::path& page, const std::string& query) {
    return medax::cli::file_url(page) + "?" + query;
  }
  medax::cli::BrowserRun launch(const std::vector<std::string>& flags) {
    const auto run = medax::cli::run_browser(medax::cli::find_chromium(), flags, dir_ / "browser.log", 25);
    INFO("headless Chromium (MEDAX_CHROMIUM or chromium on PATH; apt-get install chromium) did not finish: "
         << run.log.substr(run.log.size() > 2000 ? run.log.size() - 2000 : 0));
    REQUIRE(!run.timed_out);
    REQUIRE(run.exit_code == 0);
    return run;
  }

  std::filesystem::path dir_;
  int shots_ = 0;
};

/// The page's background (viewer.css, scene.background).
inline const std::uint8_t kWhite[3] = {255, 255, 255};

}  // namespace medax::test
