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
#include <unistd.h>

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

/// Creates the run folder and checks a file can be created in it; throws a message that says
/// which path, why, and what to do.
void create_run_folder(const fs::path& dir) {
  const std::string fix = "give a writable folder with --out";
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw std::runtime_error(fmt::format("cannot use {} as the run folder: it exists and is not a folder; "
                                         "remove it or {}", dir.string(), fix));
  const fs::path ancestor = existing_ancestor(dir.parent_path());
  if (!ancestor.empty() && !fs::is_directory(ancestor, ec))
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {} is a file, not a folder; {}",
                                         dir.string(), ancestor.string(), fix));
  fs::create_directories(dir, ec);
  if (ec)
    throw std::runtime_error(fmt::format("cannot create the run folder {}: {}; {}", dir.string(), ec.message(), fix));
  // spdlog's message names neither the cause nor the fix: open the log once ourselves first.
  const fs::path log_file = dir / "log.txt";
  const int fd = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0)
    throw std::runtime_error(fmt::format("cannot write into the run folder {}: creating {} failed: {}; {}",
                                         dir.string(), log_file.filename().string(), std::strerror(errno), fix));
  ::close(fd);
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
  std::shared_ptr<spdlog::logger> log;
  try {
    create_run_folder(options.out_dir);
    log = make_logger(options.out_dir / "log.txt", options.quiet);
    const std::string resolved = resolved_yaml(config);
    write_file_atomic(options.out_dir / "config.resolved.yaml", [&](std::ostream& out) { out << resolved; });
  } catch (const std::exception& e) {
    result.failed_stage = kRunFolderStage;
    result.error = log ? fmt::format("cannot write into the run folder {}: {}; check the free space or give "
                                     "another folder with --out", options.out_dir.string(), e.what())
                       : e.what();
    if (log) log->error("{}", result.error);
    return result;
  }
  result.wrote_log = true;
  log->info("medax {} running '{}' (seed {}) into {}", kVersion, config.name, config.seed, options.out_dir.string());

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
  try {
    scene.shape.mesh = read_mesh(config.input);
    scene.shape.source = config.input.string();
    log->info("read {}: {} vertices, {} faces", config.input.string(), scene.shape.mesh.vertices.size(),
              scene.shape.mesh.faces.size());
    if (!config.medial_input.empty()) {
      scene.medial = read_medial(config.medial_input);
      log->info("read {}: {} medial vertices", config.medial_input.string(), scene.medial->centres.size());
    }
  } catch (const std::exception& e) {
    result.failed_stage = "input";
    result.error = e.what();
    log->error("cannot read the input: {}", e.what());
    return result;
  }

  for (std::size_t i = 0; i < config.stages.size(); ++i) {
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
      detail::RunContext ctx(log, stage.id, detail::stage_seed(config.seed, stage.id), options.out_dir, work.data);
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

  try {
    write_outputs(config, scene, options.out_dir, *log);
  } catch (const std::exception& e) {
    if (result.failed_stage.empty()) result.failed_stage = "outputs";
    if (result.error.empty()) result.error = fmt::format("writing the outputs into {}: {}", options.out_dir.string(), e.what());
    log->error("writing outputs failed: {}", e.what());
  }
  try {
    nlohmann::json tj = nlohmann::json::object();
    tj["stages"] = nlohmann::json::array();
    for (const StageTiming& t : timings)
      tj["stages"].push_back({{"id", t.id}, {"plugin", t.plugin}, {"seconds", t.seconds},
                              {"peak_memory_mib", t.peak_memory_mib}, {"ok", t.ok}});
    tj["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
    detail::write_json_file(options.out_dir / "timings.json", tj);
  } catch (const std::exception& e) {
    if (result.failed_stage.empty()) result.failed_stage = "outputs";
    if (result.error.empty()) result.error = fmt::format("writing timings.json into {}: {}", options.out_dir.string(), e.what());
    log->error("writing timings.json failed: {}", e.what());
  }

  result.ok = result.failed_stage.empty();
  if (result.ok) log->info("done: results in {}", options.out_dir.string());
  else if (detail::interrupt_requested())
    log->error("run interrupted at '{}'; outputs of the stages completed before it are in {}", result.failed_stage,
               options.out_dir.string());
  else log->error("run stopped at '{}'; outputs of the stages before it are in {}", result.failed_stage,
                  options.out_dir.string());
  log->flush();
  return result;
}

}  // namespace medax
