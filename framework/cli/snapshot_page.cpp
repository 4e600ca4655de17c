#include "snapshot_page.hpp"

#include "snapshot_chromium.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace medax::cli {

namespace fs = std::filesystem;

ScratchFolder::ScratchFolder() {
  std::string pattern = (fs::temp_directory_path() / "medax-snapshot-XXXXXX").string();
  if (!::mkdtemp(pattern.data()))
    throw std::runtime_error(fmt::format("cannot create a temporary folder {}: {}", pattern, std::strerror(errno)));
  path_ = pattern;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string page_query(const SceneSettings& settings, int width, int height) {
  std::string q = fmt::format("?w={}&h={}&ui=0&view={}&zoom={}", width, height, settings.view, settings.zoom);
  if (!settings.field.empty()) q += "&field=" + settings.field;
  if (!settings.layers.empty()) q += "&layers=" + settings.layers;
  if (settings.pick >= 0) q += fmt::format("&pick={}", settings.pick);
  if (!settings.legend) q += "&legend=0";
  return q;
}

void take_picture(const fs::path& page, const SceneSettings& settings, int width, int height, const fs::path& png,
                  double timeout_seconds, const fs::path& scratch) {
  const fs::path browser = find_chromium();
  const fs::path target = fs::absolute(png);
  fs::remove(target);
  std::vector<std::string> flags = headless_flags(scratch / "profile", width, height);
  flags.push_back("--screenshot=" + target.string());
  flags.push_back(file_url(page) + page_query(settings, width, height));
  const BrowserRun run = run_browser(browser, flags, scratch / "browser.log", timeout_seconds);
  const std::vector<std::string> errors = page_errors(run.log);
  if (!errors.empty()) throw std::runtime_error(fmt::format("the viewer page reported: {}", errors.front()));
  if (run.timed_out)
    throw std::runtime_error(
        fmt::format("{} took more than {} s; raise --timeout for a large run", browser.string(), timeout_seconds));
  if (run.exit_code != 0 || !fs::exists(target)) {
    const std::string tail = run.log.substr(run.log.size() > 1500 ? run.log.size() - 1500 : 0);
    throw std::runtime_error(
        fmt::format("{} wrote no picture (exit code {}); its last words:\n{}", browser.string(), run.exit_code, tail));
  }
}

}  // namespace medax::cli
