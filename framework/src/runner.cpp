// Runs a validated pipeline into a run folder.
#include <medax/io.hpp>
#include <medax/kernel/runner.hpp>

#include "json_file.hpp"
#include "run_context.hpp"
#include "run_folder.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <ctime>
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

std::string utc_time(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  ::gmtime_r(&seconds, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

/// Every file in the run folder so far, {relative path: bytes}, for run.json: a reader tells a
/// complete run from a torn or mixed folder by comparing it with what is there.
nlohmann::json file_sizes(const fs::path& dir) {
  nlohmann::json files = nlohmann::json::object();
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[entry.path().lexically_relative(dir).generic_string()] = entry.file_size();
  return files;
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

/// One run of a pipeline: the steps of run_pipeline, each a method, sharing the run's state.
class Run {
 public:
  Run(const PipelineConfig& config, const RunOptions& options) : config_(config), options_(options) {
    result_.out_dir = options.out_dir;
  }

  /// Creates the staging folder, the log and config.resolved.yaml; false when it cannot.
  bool open() {
    try {
      folder_ = detail::create_run_folder(options_.out_dir);
    } catch (const std::exception& e) {
      result_.failed_stage = kRunFolderStage;
      result_.error = e.what();
      return false;
    }
    try {
      log_ = make_logger(dir() / "log.txt", options_.quiet);
      const std::string resolved = resolved_yaml(config_);
      write_file_atomic(dir() / "config.resolved.yaml", [&](std::ostream& out) { out << resolved; });
    } catch (const std::exception& e) {
      result_.failed_stage = kRunFolderStage;
      result_.error = fmt::format("cannot write into the run folder {}: {}; check the free space or give "
                                  "another folder with --out", options_.out_dir.string(), e.what());
      log_.reset();
      detail::discard(folder_);  // nothing ran: the previous run folder, if any, stays as it was
      return false;
    }
    result_.wrote_log = true;
    log_->info("medax {} running '{}' (seed {}) into {}", kVersion, config_.name, config_.seed,
               options_.out_dir.string());
    log_->info("writing into {}; it becomes {} when the run ends", dir().string(), folder_.target.string());
    for (const std::string& stale : folder_.removed)
      log_->warn("removed {}: the unfinished run folder of a run that was killed", stale);
    detail::install_interrupt_handler();
    return true;
  }

  /// Reads the input mesh (and `medial_input:`); false, recorded as a failure at `input`, when it cannot.
  bool read_input() {
    try {
      scene_.shape = read_shape(config_.input);
      log_->info("read {}: {}", config_.input.string(), describe_input());
      if (!config_.medial_input.empty()) {
        scene_.medial = read_medial(config_.medial_input);
        log_->info("read {}: {} medial vertices", config_.medial_input.string(), scene_.medial->centres.size());
      }
      return true;
    } catch (const std::exception& e) {
      result_.failed_stage = "input";
      result_.error = e.what();
      log_->error("cannot read the input: {}", e.what());
      return false;
    }
  }

  /// "N vertices, M faces", or for a point-set file "a point cloud of N points, no faces".
  std::string describe_input() const {
    const Shape& shape = scene_.shape;
    if (!shape.mesh.empty())
      return fmt::format("{} vertices, {} faces", shape.mesh.vertices.size(), shape.mesh.faces.size());
    const bool normals = !shape.samples.normals.empty();
    return fmt::format("a point cloud of {} points{}, no faces", shape.samples.size(), normals ? " with normals" : "");
  }

  /// Runs the stages in order until one fails or the user interrupts the run.
  void run_stages() {
    for (std::size_t i = 0; i < config_.stages.size(); ++i) {
      const StageConfig& stage = config_.stages[i];
      if (stop_if_interrupted(fmt::format("before stage '{}'", stage.id), stage.id)) return;
      if (!run_stage(stage)) return;
      if (i + 1 == config_.stages.size())
        stop_if_interrupted(fmt::format("during the last stage '{}'", stage.id), stage.id);
    }
  }

  /// The configured outputs, metrics.json and timings.json.
  void write_results() {
    try {
      write_outputs(config_, scene_, dir(), *log_);
    } catch (const std::exception& e) {
      record_output_failure(fmt::format("writing the outputs into {}: {}", options_.out_dir.string(), e.what()));
    }
  }

  /// timings.json, the log's last words, run.json (written last) and the publication.
  RunResult finish() {
    write_timings();
    result_.ok = result_.failed_stage.empty();
    log_outcome();
    try {
      detail::write_json_file(dir() / "run.json", completion_record());
      detail::publish(folder_);
    } catch (const std::exception& e) {
      const std::string error = fmt::format("cannot publish the run into {}: {}; its files are in {}",
                                            options_.out_dir.string(), e.what(), dir().string());
      log_->error("{}", error);
      if (result_.ok) result_.failed_stage = kRunFolderStage;
      result_.ok = false;
      result_.error = result_.error.empty() ? error : result_.error + "; " + error;
      result_.out_dir = dir();
    }
    log_->flush();
    return result_;
  }

  const RunResult& result() const { return result_; }

 private:
  const fs::path& dir() const { return folder_.staging; }  // everything is written here

  bool stop_if_interrupted(const std::string& where, const std::string& failed_stage) {
    if (!detail::interrupt_requested()) return false;
    result_.failed_stage = failed_stage;
    result_.signal = detail::interrupt_signal();
    result_.error = fmt::format("interrupted by {} {}", detail::signal_name(result_.signal), where);
    log_->error("{}", result_.error);
    return true;
  }

  /// Runs one stage on a copy of the scene, which replaces the scene only when the stage
  /// succeeds (a stage that fails half-way leaves the last complete state behind).
  bool run_stage(const StageConfig& stage) {
    StageTiming timing{stage.id, stage.plugin};
    std::string message;
    reset_peak_memory();
    const auto start = std::chrono::steady_clock::now();
    try {
      Scene work = scene_;
      stage.instance->prepare(work);
      detail::RunContext ctx(log_, stage.id, detail::stage_seed(config_.seed, stage.id), dir(), work.data);
      stage.instance->run(work, ctx);
      if (work.medial) work.medial->validate();
      scene_ = std::move(work);
      timing.ok = true;
    } catch (const std::exception& e) {
      result_.failed_stage = stage.id;
      message = e.what();
      if (scene_.shape.mesh.empty())  // a point cloud: say so, the stage's words may not
        message += fmt::format(" ({} is {}; docs/pointclouds.md lists the stages for point clouds)",
                               config_.input.string(), describe_input());
      result_.error = fmt::format("{}: {}", stage.id, message);  // the stage's words, under its id
    }
    timing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    timing.peak_memory_mib = read_peak_memory_mib();
    result_.timings.push_back(timing);
    if (!timing.ok && detail::interrupt_requested()) {  // the stage gave up on the signal (or failed meanwhile)
      log_->error("stage '{}' ({}) stopped after {:.3f} s: {}", stage.id, stage.plugin, timing.seconds, message);
      stop_if_interrupted(fmt::format("during stage '{}'", stage.id), stage.id);
    } else if (!timing.ok) {
      log_->error("stage '{}' ({}) failed after {:.3f} s: {}", stage.id, stage.plugin, timing.seconds, message);
    } else {
      log_->info("stage '{}' ({}) done in {:.3f} s, peak memory {:.1f} MiB", stage.id, stage.plugin, timing.seconds,
                 timing.peak_memory_mib);
    }
    return timing.ok;
  }

  void record_output_failure(const std::string& error) {
    if (result_.failed_stage.empty()) result_.failed_stage = "outputs";
    if (result_.error.empty()) result_.error = error;
    log_->error("{}", error);
  }

  void write_timings() {
    try {
      nlohmann::json tj = nlohmann::json::object();
      tj["stages"] = nlohmann::json::array();
      for (const StageTiming& t : result_.timings)
        tj["stages"].push_back({{"id", t.id}, {"plugin", t.plugin}, {"seconds", t.seconds},
                                {"peak_memory_mib", t.peak_memory_mib}, {"ok", t.ok}});
      tj["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_).count();
      detail::write_json_file(dir() / "timings.json", tj);
    } catch (const std::exception& e) {
      record_output_failure(fmt::format("writing timings.json into {}: {}", options_.out_dir.string(), e.what()));
    }
  }

  void log_outcome() {
    const std::string& out = options_.out_dir.string();
    if (result_.ok) log_->info("done: results in {}", out);
    else if (result_.signal)
      log_->error("run interrupted at '{}'; outputs of the stages completed before it are in {}", result_.failed_stage,
                  out);
    else log_->error("run stopped at '{}'; outputs of the stages before it are in {}", result_.failed_stage, out);
    log_->flush();
  }

  /// run.json: how the run ended. A folder without it is not a finished run.
  nlohmann::json completion_record() const {
    const auto or_null = [](const std::string& text) { return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text); };
    nlohmann::json marker;
    marker["status"] = result_.ok ? "ok" : result_.signal ? "interrupted" : "failed";
    marker["failed_stage"] = or_null(result_.failed_stage);
    marker["error"] = or_null(result_.error);
    marker["signal"] = result_.signal ? nlohmann::json(detail::signal_name(result_.signal)) : nlohmann::json(nullptr);
    marker["medax_version"] = kVersion;
    marker["pipeline"] = config_.name;
    marker["started"] = utc_time(started_);
    marker["ended"] = utc_time(std::chrono::system_clock::now());
    marker["files"] = file_sizes(dir());
    return marker;
  }

  const PipelineConfig& config_;
  const RunOptions& options_;
  RunResult result_;
  detail::RunFolder folder_;
  std::shared_ptr<spdlog::logger> log_;
  Scene scene_;
  const std::chrono::system_clock::time_point started_ = std::chrono::system_clock::now();
  const std::chrono::steady_clock::time_point run_start_ = std::chrono::steady_clock::now();
};

}  // namespace

RunResult run_pipeline(const PipelineConfig& config, const RunOptions& options) {
  Run run(config, options);
  if (!run.open()) return run.result();
  if (run.read_input()) {
    run.run_stages();
    run.write_results();
  }
  return run.finish();
}

}  // namespace medax
