#pragma once
// Headless Chromium, as `medax snapshot` drives it: one process per picture, killed (with its
// children) when it takes too long.
#include <filesystem>
#include <string>
#include <vector>

namespace medax::cli {

/// $MEDAX_CHROMIUM, else the first of chromium, chromium-browser, google-chrome on PATH. Throws
/// saying how to install it when there is none.
std::filesystem::path find_chromium();

struct BrowserRun {
  int exit_code = -1;  ///< the browser's exit code; -1 when it was killed or did not start
  bool timed_out = false;
  std::string log;  ///< what it wrote on stdout and stderr
};

/// The flags every headless run needs: no sandbox as root (Chromium refuses to start there
/// otherwise), software WebGL, a throw-away profile in `profile`, a window of `width` x `height`.
std::vector<std::string> headless_flags(const std::filesystem::path& profile, int width, int height);

/// Runs `browser` with `args`, its output into `log_file`; kills it after `timeout_seconds`.
BrowserRun run_browser(const std::filesystem::path& browser, const std::vector<std::string>& args,
                       const std::filesystem::path& log_file, double timeout_seconds);

/// The file:// URL of `file` (made absolute), percent-encoded so that a space, '#' or '?' in a
/// folder name is part of the path.
std::string file_url(const std::filesystem::path& file);

/// The lines of `log` where the page reported an error (viewer.js prefixes them with
/// "medax-viewer error:"; an uncaught exception reads "Uncaught ...").
std::vector<std::string> page_errors(const std::string& log);

}  // namespace medax::cli
