#include "run_folder.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace medax::detail {

namespace fs = std::filesystem;

namespace {

/// The first existing ancestor of `path` (itself included), or empty.
fs::path existing_ancestor(const fs::path& path) {
  std::error_code ec;
  for (fs::path p = path; !p.empty(); p = p.parent_path()) {
    if (fs::exists(p, ec)) return p;
    if (p == p.parent_path()) break;
  }
  return {};
}

/// A run is written into `staging`, a fresh folder beside `target`, and renamed into place
/// when it ends (see docs/pipeline-format.md, "What a run folder guarantees").

/// `path` without a trailing separator, "." or "..", so that it has a file name.
/// Absolute, so that it has a parent folder for the staging folder.
fs::path plain_path(const fs::path& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  if (p.has_relative_path() && p.filename().empty()) p = p.parent_path();
  return p;
}

std::optional<long> staging_pid(const std::string& name, const std::string& target_name) {
  for (const char* tag : {".partial-", ".replaced-"}) {
    const std::string prefix = target_name + tag;
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return std::nullopt;
    return std::stol(digits);
  }
  return std::nullopt;
}

/// True when `pid` is a running process other than this one (a zombie is dead: in a container
/// nobody may reap it).
bool running_elsewhere(long pid) {
  if (pid == ::getpid()) return false;
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) return false;
  std::ifstream stat(fmt::format("/proc/{}/stat", pid));
  std::string line;
  if (!std::getline(stat, line)) return true;
  const auto state = line.rfind(") ");  // "pid (comm) S ...": comm may hold spaces and parentheses
  return state == std::string::npos || (line[state + 2] != 'Z' && line[state + 2] != 'X');
}

/// True when `pid` still runs after a short grace: a run whose sweep was killed gets SIGKILL
/// (PR_SET_PDEATHSIG) at that moment, and the resumed sweep may reach its folder before it is gone.
bool alive_elsewhere(long pid) {
  for (int i = 0; i < 100 && running_elsewhere(pid); ++i) ::usleep(20000);
  return running_elsewhere(pid);
}

/// Files of `dir` that are this process's stdout or stderr (a caller capturing the run's
/// console into the run folder, like a sweep job's output.txt): they belong to this run.
std::vector<fs::path> own_console_files(const fs::path& dir) {
  std::vector<fs::path> out;
  struct stat console[2];
  bool have[2];
  for (int fd : {1, 2}) have[fd - 1] = ::fstat(fd, &console[fd - 1]) == 0 && S_ISREG(console[fd - 1].st_mode);
  if (!have[0] && !have[1]) return out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    struct stat st;
    if (::lstat(entry.path().c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    for (int i = 0; i < 2; ++i)
      if (have[i] && st.st_dev == console[i].st_dev && st.st_ino == console[i].st_ino) {
        out.push_back(entry.path());
        break;
      }
  }
  return out;
}

bool is_run_folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "run.json", ec) || fs::is_regular_file(dir / "config.resolved.yaml", ec);
}

/// Throws unless `dir` (an existing folder) may be replaced by a run: it is empty, holds only
/// this run's console files, or is a medax run folder.
void check_replaceable(const fs::path& dir, const fs::path& shown) {
  if (is_run_folder(dir)) return;
  const std::vector<fs::path> own = own_console_files(dir);
  std::error_code ec;
  std::size_t count = 0;
  std::string example;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (std::find(own.begin(), own.end(), entry.path()) != own.end()) continue;
    if (count++ == 0) example = entry.path().filename().string();
  }
  if (ec)
    throw std::runtime_error(fmt::format("cannot use {} as the run folder: cannot list it: {}; give another folder "
                                         "with --out", shown.string(), ec.message()));
  if (count == 0) return;
  throw std::runtime_error(fmt::format(
      "cannot use {} as the run folder: it holds {} entr{} (e.g. '{}') and is not a medax run folder (it has no "
      "run.json or config.resolved.yaml), so medax will not replace it; give a new or empty folder with --out, "
      "or move its contents away",
      shown.string(), count, count == 1 ? "y" : "ies", example));
}

void sync_folder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

namespace {

constexpr const char* kGiveWritableFolder = "give a writable folder with --out";

/// The folder a run publishes into: `dir` itself or where a link the user made points. A link
/// left by a killed run is removed; one of a live run is refused.
fs::path resolve_target(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw std::runtime_error(fmt::format("cannot use {} as the run folder: it exists and is not a folder; "
                                         "remove it or {}", dir.string(), kGiveWritableFolder));
  const fs::path ancestor = existing_ancestor(dir.parent_path());
  if (!ancestor.empty() && !fs::is_directory(ancestor, ec))
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {} is a file, not a folder; {}",
                                         dir.string(), ancestor.string(), kGiveWritableFolder));
  fs::path target = plain_path(dir);
  if (!fs::is_symlink(target, ec)) return target;
  const fs::path to = fs::read_symlink(target, ec);
  const auto pid = ec ? std::nullopt : staging_pid(to.filename().string(), target.filename().string());
  if (pid && alive_elsewhere(*pid))
    throw std::runtime_error(fmt::format("cannot use {} as the run folder: another medax run (process {}) is "
                                         "writing into it; wait for it to end or give another folder with --out",
                                         dir.string(), *pid));
  if (pid) {
    fs::remove(target, ec);  // the live link of a killed run: its folder is removed later
    return target;
  }
  target = fs::canonical(target, ec);  // a link the user made: publish where it points
  if (ec)
    throw std::runtime_error(fmt::format("cannot use {} as the run folder: it is a link that leads nowhere "
                                         "({}); remove it or {}", dir.string(), ec.message(), kGiveWritableFolder));
  return target;
}

/// Removes the staging folders that runs killed before publishing (kill -9, power loss) left
/// beside the target; returns those removed.
std::vector<std::string> remove_stale_staging(const fs::path& parent, const std::string& name) {
  std::vector<std::string> removed;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const auto pid = staging_pid(entry.path().filename().string(), name);
    if (!pid || alive_elsewhere(*pid)) continue;
    std::error_code failed;
    fs::remove_all(entry.path(), failed);
    if (!failed) removed.push_back(entry.path().string());
  }
  return removed;
}

/// Creates the staging folder's log.txt, so that a folder nobody can write into is reported with
/// its cause and fix (spdlog's message names neither).
void create_log(const fs::path& staging, const fs::path& dir) {
  const fs::path log_file = staging / "log.txt";
  const int fd = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd >= 0) {
    ::close(fd);
    return;
  }
  const int err = errno;
  std::error_code ec;
  fs::remove_all(staging, ec);
  throw std::runtime_error(fmt::format("cannot write into the run folder {}: creating {} failed: {}; {}",
                                       dir.string(), log_file.filename().string(), std::strerror(err),
                                       kGiveWritableFolder));
}

}  // namespace

/// Checks the target, removes stale staging folders of killed runs into it, creates the staging
/// folder and its log; throws a message that says which path, why, and what to do.
RunFolder create_run_folder(const fs::path& dir) {
  RunFolder folder;
  folder.target = resolve_target(dir);
  const fs::path parent = folder.target.parent_path();
  const std::string name = folder.target.filename().string();
  std::error_code ec;
  if (fs::is_directory(folder.target, ec)) check_replaceable(folder.target, dir);
  fs::create_directories(parent, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot create the run folder {}: {}; {}", dir.string(), ec.message(), kGiveWritableFolder));
  folder.removed = remove_stale_staging(parent, name);
  folder.staging = parent / fmt::format("{}.partial-{}", name, ::getpid());
  if (!fs::create_directory(folder.staging, ec))
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {}; {}", dir.string(),
                                         ec ? ec.message() : std::string("the staging folder exists"),
                                         kGiveWritableFolder));
  create_log(folder.staging, dir);
  // A fresh target shows the run while it goes (its log can be followed at <out>/log.txt).
  if (!fs::exists(folder.target, ec) && !fs::is_symlink(folder.target, ec)) {
    fs::create_directory_symlink(folder.staging.filename(), folder.target, ec);
    folder.linked = !ec;
  }
  return folder;
}

/// Removes a staging folder that will not be published (and the link to it).
void discard(const RunFolder& folder) {
  std::error_code ec;
  if (folder.linked) fs::remove(folder.target, ec);
  fs::remove_all(folder.staging, ec);
}

/// Renames the staging folder into place; a previous run folder there is replaced in one step
/// (exchanged, then removed). Throws, leaving the staging folder, when the target may not be replaced.
void publish(const RunFolder& folder) {
  std::error_code ec;
  sync_folder(folder.staging);
  if (folder.linked || fs::is_symlink(folder.target, ec)) {
    const fs::path to = fs::read_symlink(folder.target, ec);
    if (!ec && to == folder.staging.filename()) fs::remove(folder.target, ec);
  }
  if (!fs::exists(folder.target, ec) && !fs::is_symlink(folder.target, ec)) {
    fs::rename(folder.staging, folder.target, ec);
    if (ec)
      throw std::runtime_error(fmt::format("cannot rename {} to {}: {}", folder.staging.string(),
                                           folder.target.string(), ec.message()));
    sync_folder(folder.target.parent_path());
    return;
  }
  if (!fs::is_directory(folder.target, ec))
    throw std::runtime_error(fmt::format("{} appeared during the run and is not a folder", folder.target.string()));
  check_replaceable(folder.target, folder.target);
  // This run's console capture (e.g. a sweep job's output.txt) moves along, still open.
  for (const fs::path& file : own_console_files(folder.target)) {
    const fs::path into = folder.staging / file.filename();
    if (!fs::exists(into, ec)) fs::rename(file, into, ec);
  }
  if (::renameat2(AT_FDCWD, folder.staging.c_str(), AT_FDCWD, folder.target.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(folder.staging, ec);  // now the previous run
  } else {
    // No atomic exchange on this file system: move the previous run aside first. A kill in
    // between leaves <out>.replaced-<pid> and <out>.partial-<pid>, removed by the next run.
    const fs::path aside = folder.target.parent_path() /
                           fmt::format("{}.replaced-{}", folder.target.filename().string(), ::getpid());
    fs::rename(folder.target, aside, ec);
    if (ec)
      throw std::runtime_error(fmt::format("cannot move the previous run {} aside: {}", folder.target.string(),
                                           ec.message()));
    fs::rename(folder.staging, folder.target, ec);
    if (ec) {
      std::error_code back;
      fs::rename(aside, folder.target, back);
      throw std::runtime_error(fmt::format("cannot rename {} to {}: {}", folder.staging.string(),
                                           folder.target.string(), ec.message()));
    }
    fs::remove_all(aside, ec);
  }
  sync_folder(folder.target.parent_path());
}

}  // namespace medax::detail
