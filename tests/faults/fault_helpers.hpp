#pragma once
// Fault injection for the `medax` binary: signals at seeded random moments, a file-size limit,
// and the checks every fault must pass (docs/pipeline-format.md, "What a run folder guarantees").
#include "cli_helpers.hpp"

#include <medax/io.hpp>

#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <iterator>
#include <cstring>
#include <map>
#include <random>
#include <thread>

namespace medax::test {

/// The fixed "random" moments (ms after the start) at which a fault strikes: seeded, so every
/// run of the suite injects the same faults.
inline std::vector<int> seeded_delays_ms(unsigned seed, std::size_t count, int max_ms) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> ms(0, max_ms);
  std::vector<int> out(count);
  for (int& d : out) d = ms(rng);
  return out;
}

/// How a spawned medax ended.
struct Ending {
  int status = 0;
  bool signalled() const { return WIFSIGNALED(status); }
  int code() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
};

/// Starts `medax ARGS`, sends `sig` after `delay_ms` (a no-op when it has already ended) and waits.
inline Ending run_and_kill(const std::vector<std::string>& args, const std::string& plugin_path,
                           const std::filesystem::path& dir, int sig, int delay_ms) {
  const pid_t pid = spawn_medax(args, plugin_path, dir);
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  ::kill(pid, sig);  // the zombie of a finished child ignores it
  Ending ending;
  REQUIRE(::waitpid(pid, &ending.status, 0) == pid);
  return ending;
}

/// Starts `medax ARGS`, sends `sig` as soon as `log(pid)` contains `text` (or when it ends) and waits.
template <typename LogOf>
Ending run_and_kill_at(const std::vector<std::string>& args, const std::string& plugin_path,
                       const std::filesystem::path& dir, int sig, LogOf log, const std::string& text) {
  const pid_t pid = spawn_medax(args, plugin_path, dir);
  Ending ending;
  for (int polls = 0; polls < 20000; ++polls) {  // at most ~20 s
    if (::waitpid(pid, &ending.status, WNOHANG) == pid) return ending;  // it ended before the line
    std::ifstream in(log(pid));
    const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (content.find(text) != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ::kill(pid, sig);
  REQUIRE(::waitpid(pid, &ending.status, 0) == pid);
  return ending;
}

/// A limit on the size of the files the process (and the medax it starts) may write, while in scope.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    const rlimit limit{bytes, saved_.rlim_max};
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &limit) == 0);
  }
  ~FileSizeLimit() { ::setrlimit(RLIMIT_FSIZE, &saved_); }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
};

/// `medax ARGS` under a file-size limit of `bytes` (stdout and stderr into `Output::err`, through a
/// pipe, which the limit does not cut).
inline Output run_medax_capped(const std::string& args, const std::string& plugin_path, rlim_t bytes) {
  const std::string command = "MEDAX_PLUGIN_PATH='" + plugin_path + "' '" +
                              (std::filesystem::path(MEDAX_BINARY_DIR) / "bin" / "medax").string() + "' " + args + " 2>&1";
  Output result;
  const FileSizeLimit capped(bytes);
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.err.append(buffer, n);
  const int status = ::pclose(pipe);
  result.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

/// A tmpfs of `bytes` mounted at `at` while in scope (a stale one there is unmounted first). Tests
/// run as root in CI; mount must work (a failure fails the test, never skips it).
class SmallDisk {
 public:
  SmallDisk(const std::filesystem::path& at, std::size_t bytes) : at_(at) {
    ::umount2(at.c_str(), MNT_DETACH);
    std::filesystem::create_directories(at);
    const std::string options = "size=" + std::to_string(bytes);
    INFO("mount -t tmpfs -o " << options << " " << at.string() << ": " << std::strerror(errno));
    REQUIRE(::mount("tmpfs", at.c_str(), "tmpfs", 0, options.c_str()) == 0);
  }
  ~SmallDisk() { ::umount2(at_.c_str(), MNT_DETACH); }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

 private:
  std::filesystem::path at_;
};

/// Every file under `dir` (relative path -> content); empty when `dir` does not exist.
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[entry.path().lexically_relative(dir).generic_string()] = read_text(entry.path());
  return files;
}

/// Checks that `dir` holds one complete run: run.json lists exactly the files present (beside
/// `extra`, files others add: a sweep's output.txt, status.json), with their sizes, and every
/// file parses. Returns run.json.
inline nlohmann::json check_complete_run(const std::filesystem::path& dir, const std::vector<std::string>& extra = {}) {
  INFO("run folder " << dir.string());
  REQUIRE(std::filesystem::is_regular_file(dir / "run.json"));
  const nlohmann::json run = nlohmann::json::parse(read_text(dir / "run.json"));
  const std::string status = run.value("status", "");
  CHECK((status == "ok" || status == "failed" || status == "interrupted"));
  REQUIRE(run.contains("files"));
  auto present = snapshot(dir);
  present.erase("run.json");
  for (const std::string& name : extra) present.erase(name);
  std::map<std::string, std::size_t> listed, found;
  for (const auto& [name, bytes] : run["files"].items()) listed[name] = bytes.get<std::size_t>();
  for (const auto& [name, content] : present) found[name] = content.size();
  CHECK(found == listed);  // nothing torn, nothing missing, nothing of another run
  for (const auto& [name, content] : present) {
    INFO(name);
    if (name.size() > 5 && name.substr(name.size() - 5) == ".json") CHECK_NOTHROW(nlohmann::json::parse(content));
    if (name.size() > 3 && name.substr(name.size() - 3) == ".ma") CHECK_NOTHROW(read_medial(dir / name));
    CHECK(name.find(".tmp") == std::string::npos);
  }
  CHECK(present.count("config.resolved.yaml") == 1);
  CHECK(present.count("log.txt") == 1);
  return run;
}

/// Names in `parent` left by unfinished runs: `*.partial-*`, `*.replaced-*`, `*.tmp*`.
inline std::vector<std::string> debris(const std::filesystem::path& parent) {
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(parent)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".partial-") != std::string::npos || name.find(".replaced-") != std::string::npos ||
        name.find(".tmp") != std::string::npos)
      out.push_back(entry.path().string());
  }
  return out;
}

}  // namespace medax::test
