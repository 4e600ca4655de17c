#include "snapshot_chromium.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace medax::cli {

namespace fs = std::filesystem;

fs::path find_chromium() {
  if (const char* env = std::getenv("MEDAX_CHROMIUM"); env && *env) return env;
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "/usr/bin:/bin");
  std::vector<fs::path> dirs;
  for (std::string dir; std::getline(folders, dir, ':');) dirs.push_back(dir);
  for (const char* name : {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"})
    for (const fs::path& dir : dirs)
      if (::access((dir / name).c_str(), X_OK) == 0) return dir / name;
  throw std::runtime_error(
      "snapshot needs headless Chromium and none is on PATH; install Debian's chromium "
      "(apt-get install chromium) or set MEDAX_CHROMIUM to the browser's path");
}

std::vector<std::string> headless_flags(const fs::path& profile, int width, int height) {
  std::vector<std::string> flags{"--headless",
                                 "--disable-gpu",
                                 "--enable-unsafe-swiftshader",
                                 "--hide-scrollbars",
                                 "--no-first-run",
                                 "--no-default-browser-check",
                                 "--disable-extensions",
                                 "--force-device-scale-factor=1",
                                 "--enable-logging=stderr",
                                 "--v=0",
                                 "--user-data-dir=" + profile.string(),
                                 fmt::format("--window-size={},{}", width, height)};
  if (::geteuid() == 0) flags.push_back("--no-sandbox");
  return flags;
}

namespace {

/// Waits for `pid`; after `timeout_seconds` kills its process group. Returns the wait status or -1.
int wait_or_kill(pid_t pid, double timeout_seconds, bool& timed_out) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      timed_out = true;
      ::kill(-pid, SIGKILL);  // the browser and its renderer and GPU processes
      ::waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return status;
}

}  // namespace

BrowserRun run_browser(const fs::path& browser, const std::vector<std::string>& args, const fs::path& log_file,
                       double timeout_seconds) {
  std::vector<std::string> words{browser.string()};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  pid_t pid = 0;
  const int error = ::posix_spawn(&pid, argv[0], &files, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attributes);
  BrowserRun run;
  if (error != 0) {
    run.log = fmt::format("cannot start {}: {}", browser.string(), std::strerror(error));
    return run;
  }
  const int status = wait_or_kill(pid, timeout_seconds, run.timed_out);
  if (status >= 0 && WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  std::ifstream in(log_file);
  std::ostringstream text;
  text << in.rdbuf();
  run.log = text.str();
  return run;
}

std::string file_url(const fs::path& file) {
  std::string url = "file://";
  for (unsigned char c : fs::absolute(file).lexically_normal().string()) {
    if (std::isalnum(c) || std::strchr("/-._~", c)) url += static_cast<char>(c);
    else url += fmt::format("%{:02X}", c);
  }
  return url;
}

std::vector<std::string> page_errors(const std::string& log) {
  std::vector<std::string> errors;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    if (line.find("CONSOLE") != std::string::npos &&
        (line.find("medax-viewer error:") != std::string::npos || line.find("Uncaught") != std::string::npos))
      errors.push_back(line);
  return errors;
}

}  // namespace medax::cli
