// Runs a validated pipeline into a run folder.
#include <medax/io.hpp>
#include <medax/kernel/runner.hpp>

#include "json_file.hpp"
#include "run_context.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <optional>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>

namespace medax {

namespace fs = std::filesystem;

namespace {

/// Resets the kernel's peak-RSS mark so the next reading is this stage's own peak (Linux).
void reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  if (clear) clear << "5";
}

double read_peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

/// RunResult::failed_stage when the run folder or its log cannot be created (nothing ran).
constexpr const char* kRunFolderStage = "run folder";

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
struct RunFolder {
  fs::path target;   ///< where the run is published (as given with --out)
  fs::path staging;  ///< <target>.partial-<pid>
  bool linked = false;               ///< target is a symbolic link to staging while the run goes
  std::vector<std::string> removed;  ///< stale staging folders of killed runs, removed
};

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

/// True when `pid` is a live process other than this one.
bool alive_elsewhere(long pid) {
  if (pid == ::getpid()) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
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

/// Checks the target, removes stale staging folders of killed runs into it, creates the staging
/// folder and its log; throws a message that says which path, why, and what to do.
RunFolder create_run_folder(const fs::path& dir) {
  const std::string fix = "give a writable folder with --out";
  RunFolder folder;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw std::runtime_error(fmt::format("cannot use {} as the run folder: it exists and is not a folder; "
                                         "remove it or {}", dir.string(), fix));
  const fs::path ancestor = existing_ancestor(dir.parent_path());
  if (!ancestor.empty() && !fs::is_directory(ancestor, ec))
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {} is a file, not a folder; {}",
                                         dir.string(), ancestor.string(), fix));
  folder.target = plain_path(dir);
  if (fs::is_symlink(folder.target, ec)) {
    const fs::path to = fs::read_symlink(folder.target, ec);
    const auto pid = ec ? std::nullopt : staging_pid(to.filename().string(), folder.target.filename().string());
    if (pid && alive_elsewhere(*pid)) {
      throw std::runtime_error(fmt::format("cannot use {} as the run folder: another medax run (process {}) is "
                                           "writing into it; wait for it to end or give another folder with --out",
                                           dir.string(), *pid));
    } else if (pid) {
      fs::remove(folder.target, ec);  // the live link of a killed run: its folder is removed below
    } else {
      folder.target = fs::canonical(folder.target, ec);  // a link the user made: publish where it points
      if (ec)
        throw std::runtime_error(fmt::format("cannot use {} as the run folder: it is a link that leads nowhere "
                                             "({}); remove it or {}", dir.string(), ec.message(), fix));
    }
  }
  const fs::path parent = folder.target.parent_path();
  const std::string name = folder.target.filename().string();
  if (fs::is_directory(folder.target, ec)) check_replaceable(folder.target, dir);
  fs::create_directories(parent, ec);
  if (ec)
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {}; {}", dir.string(), ec.message(), fix));
  // Staging folders left by runs that were killed (kill -9, power loss) before publishing.
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const auto pid = staging_pid(entry.path().filename().string(), name);
    if (!pid || alive_elsewhere(*pid)) continue;
    std::error_code removed;
    fs::remove_all(entry.path(), removed);
    if (!removed) folder.removed.push_back(entry.path().string());
  }
  folder.staging = parent / fmt::format("{}.partial-{}", name, ::getpid());
  if (!fs::create_directory(folder.staging, ec))
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {}; {}", dir.string(),
                                         ec ? ec.message() : std::string("the staging folder exists"), fix));
  // spdlog's message names neither the cause nor the fix: open the log once ourselves first.
  const fs::path log_file = folder.staging / "log.txt";
  const int fd = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    fs::remove_all(folder.staging, ec);
    throw std::runtime_error(fmt::format("cannot write into the run folder {}: creating {} failed: {}; {}",
                                         dir.string(), log_file.filename().string(), std::strerror(err), fix));
  }
  ::close(fd);
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

std::string utc_time(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  ::gmtime_r(&seconds, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::shared_ptr<spdlog::logger> make_logger(const fs::path& log_file, bool quiet) {
  std::vector<spdlog::sink_ptr> sinks;
  sinks.push_back(std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_file.string(), true));
  if (!quiet) sinks.push_back(std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  auto logger = std::make_shared<spdlog::logger>("medax", sinks.begin(), sinks.end());
  logger->set_pattern("[%H:%M:%S.%e] %^%l%$ %v");
  logger->flush_on(spdlog::level::info);
  return logger;
}

nlohmann::json metrics_json(const Scene& scene) {
  nlohmann::json all = nlohmann::json::object();
  for (const auto& [stage, metrics] : scene.metrics) {
    nlohmann::json m = nlohmann::json::object();
    for (const auto& [name, value] : metrics)
      m[name] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
    all[stage] = m;
  }
  return all;
}

/// Writes the configured outputs of the scene as it stands.
void write_outputs(const PipelineConfig& config, const Scene& scene, const fs::path& dir, spdlog::logger& log) {
  const Similarity frame = config.outputs.input_frame ? scene.shape.to_input : Similarity{};
  if (scene.medial) {
    MedialComplex medial = *scene.medial;
    medial.transform(frame);
    for (const std::string& ext : config.outputs.medial) {
      write_medial(dir / ("medial." + ext), medial);
      log.info("wrote medial.{} ({} vertices, {} edges, {} faces)", ext, medial.centres.size(),
               medial.edges.size(), medial.faces.size());
    }
  }
  if (!scene.shape.mesh.empty() && !config.outputs.surface.empty()) {
    SurfaceMesh surface = scene.shape.mesh;
    for (Vec3& v : surface.vertices) v = frame.apply(v);
    for (const std::string& ext : config.outputs.surface) {
      write_mesh(dir / ("surface." + ext), surface);
      log.info("wrote surface.{}", ext);
    }
  }
  for (const SceneData::Output& output : scene.data.outputs()) {
    write_file_atomic(dir / output.file, output.write);
    log.info("wrote {}", output.file);
  }
  detail::write_json_file(dir / "metrics.json", metrics_json(scene));
}

}  // namespace

RunResult run_pipeline(const PipelineConfig& config, const RunOptions& options) {
  RunResult result;
  result.out_dir = options.out_dir;
  const auto started = std::chrono::system_clock::now();
  std::shared_ptr<spdlog::logger> log;
  RunFolder folder;
  try {
    folder = create_run_folder(options.out_dir);
  } catch (const std::exception& e) {
    result.failed_stage = kRunFolderStage;
    result.error = e.what();
    return result;
  }
  const fs::path& dir = folder.staging;  // everything is written here, published at the end
  try {
    log = make_logger(dir / "log.txt", options.quiet);
    const std::string resolved = resolved_yaml(config);
    write_file_atomic(dir / "config.resolved.yaml", [&](std::ostream& out) { out << resolved; });
  } catch (const std::exception& e) {
    result.failed_stage = kRunFolderStage;
    result.error = fmt::format("cannot write into the run folder {}: {}; check the free space or give "
                               "another folder with --out", options.out_dir.string(), e.what());
    log.reset();
    discard(folder);  // nothing ran: the previous run folder, if any, stays as it was
    return result;
  }
  result.wrote_log = true;
  log->info("medax {} running '{}' (seed {}) into {}", kVersion, config.name, config.seed, options.out_dir.string());
  log->info("writing into {}; it becomes {} when the run ends", dir.string(), folder.target.string());
  for (const std::string& stale : folder.removed)
    log->warn("removed {}: the unfinished run folder of a run that was killed", stale);

  detail::install_interrupt_handler();
  std::vector<StageTiming>& timings = result.timings;
  const auto run_start = std::chrono::steady_clock::now();
  const auto stop_if_interrupted = [&](const std::string& where, const std::string& failed_stage) {
    if (!detail::interrupt_requested()) return false;
    result.failed_stage = failed_stage;
    result.signal = detail::interrupt_signal();
    result.error = fmt::format("interrupted by {} {}", detail::signal_name(result.signal), where);
    log->error("{}", result.error);
    return true;
  };
  Scene scene;
  bool input_read = false;
  try {
    scene.shape.mesh = read_mesh(config.input);
    scene.shape.source = config.input.string();
    log->info("read {}: {} vertices, {} faces", config.input.string(), scene.shape.mesh.vertices.size(),
              scene.shape.mesh.faces.size());
    if (!config.medial_input.empty()) {
      scene.medial = read_medial(config.medial_input);
      log->info("read {}: {} medial vertices", config.medial_input.string(), scene.medial->centres.size());
    }
    input_read = true;
  } catch (const std::exception& e) {
    result.failed_stage = "input";
    result.error = e.what();
    log->error("cannot read the input: {}", e.what());
  }

  for (std::size_t i = 0; input_read && i < config.stages.size(); ++i) {
    const StageConfig& stage = config.stages[i];
    if (stop_if_interrupted(fmt::format("before stage '{}'", stage.id), stage.id)) break;
    StageTiming timing{stage.id, stage.plugin};
    std::string message;
    reset_peak_memory();
    const auto start = std::chrono::steady_clock::now();
    try {
      // Work on a copy, so a stage that fails half-way leaves the last complete state behind.
      Scene work = scene;
      stage.instance->prepare(work);
      detail::RunContext ctx(log, stage.id, detail::stage_seed(config.seed, stage.id), dir, work.data);
      stage.instance->run(work, ctx);
      if (work.medial) work.medial->validate();
      scene = std::move(work);
      timing.ok = true;
    } catch (const std::exception& e) {
      result.failed_stage = stage.id;
      message = e.what();
      result.error = fmt::format("{}: {}", stage.id, message);  // the stage's words, under its id
    }
    timing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    timing.peak_memory_mib = read_peak_memory_mib();
    timings.push_back(timing);
    if (!timing.ok && detail::interrupt_requested()) {  // the stage gave up on the signal (or failed meanwhile)
      log->error("stage '{}' ({}) stopped after {:.3f} s: {}", stage.id, stage.plugin, timing.seconds, message);
      stop_if_interrupted(fmt::format("during stage '{}'", stage.id), stage.id);
      break;
    }
    if (!timing.ok) {
      log->error("stage '{}' ({}) failed after {:.3f} s: {}", stage.id, stage.plugin, timing.seconds, message);
      break;
    }
    log->info("stage '{}' ({}) done in {:.3f} s, peak memory {:.1f} MiB", stage.id, stage.plugin, timing.seconds,
              timing.peak_memory_mib);
    if (i + 1 == config.stages.size() &&
        stop_if_interrupted(fmt::format("during the last stage '{}'", stage.id), stage.id))
      break;
  }

  if (input_read) {
    try {
      write_outputs(config, scene, dir, *log);
    } catch (const std::exception& e) {
      if (result.failed_stage.empty()) result.failed_stage = "outputs";
      if (result.error.empty()) result.error = fmt::format("writing the outputs into {}: {}", options.out_dir.string(), e.what());
      log->error("writing outputs failed: {}", e.what());
    }
  }
  try {
    nlohmann::json tj = nlohmann::json::object();
    tj["stages"] = nlohmann::json::array();
    for (const StageTiming& t : timings)
      tj["stages"].push_back({{"id", t.id}, {"plugin", t.plugin}, {"seconds", t.seconds},
                              {"peak_memory_mib", t.peak_memory_mib}, {"ok", t.ok}});
    tj["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
    detail::write_json_file(dir / "timings.json", tj);
  } catch (const std::exception& e) {
    if (result.failed_stage.empty()) result.failed_stage = "outputs";
    if (result.error.empty()) result.error = fmt::format("writing timings.json into {}: {}", options.out_dir.string(), e.what());
    log->error("writing timings.json failed: {}", e.what());
  }

  result.ok = result.failed_stage.empty();
  const std::string status = result.ok ? "ok" : result.signal ? "interrupted" : "failed";
  if (result.ok) log->info("done: results in {}", options.out_dir.string());
  else if (result.signal)
    log->error("run interrupted at '{}'; outputs of the stages completed before it are in {}", result.failed_stage,
               options.out_dir.string());
  else log->error("run stopped at '{}'; outputs of the stages before it are in {}", result.failed_stage,
                  options.out_dir.string());
  log->flush();

  // The completion marker, written last: a folder without it is not a finished run.
  try {
    nlohmann::json marker;
    marker["status"] = status;
    marker["failed_stage"] = result.failed_stage.empty() ? nlohmann::json(nullptr) : nlohmann::json(result.failed_stage);
    marker["error"] = result.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(result.error);
    marker["signal"] = result.signal ? nlohmann::json(detail::signal_name(result.signal)) : nlohmann::json(nullptr);
    marker["medax_version"] = kVersion;
    marker["pipeline"] = config.name;
    marker["started"] = utc_time(started);
    marker["ended"] = utc_time(std::chrono::system_clock::now());
    detail::write_json_file(dir / "run.json", marker);
    publish(folder);
  } catch (const std::exception& e) {
    const std::string error = fmt::format("cannot publish the run into {}: {}; its files are in {}",
                                          options.out_dir.string(), e.what(), dir.string());
    log->error("{}", error);
    log->flush();
    if (result.ok) result.failed_stage = kRunFolderStage;
    result.ok = false;
    result.error = result.error.empty() ? error : result.error + "; " + error;
    result.out_dir = dir;
  }
  log->flush();
  return result;
}

}  // namespace medax
