#pragma once
// A viewer page rendered to a PNG by headless Chromium: what `medax snapshot` and the thumbnails
// of an experiment's results.html are made with.
#include "view_command.hpp"

#include <filesystem>
#include <string>

namespace medax::cli {

/// A fresh temporary folder (for a page, the browser's profile and its log), removed at the end.
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The page's URL query for `settings` at width x height (framework/viewer/viewer.js reads it).
std::string page_query(const SceneSettings& settings, int width, int height);

/// Renders `page` with `settings` into `png` (width x height); throws with the page's error, the
/// time-out, or the browser's last words when no picture was written.
void take_picture(const std::filesystem::path& page, const SceneSettings& settings, int width, int height,
                  const std::filesystem::path& png, double timeout_seconds, const std::filesystem::path& scratch);

}  // namespace medax::cli
