#pragma once
// The Context a stage gets inside `medax run`: logs to log.txt (and stderr), rate-limited
// progress, Ctrl-C cancellation, a per-stage seeded RNG, and outputs into the run folder.
#include <medax/context.hpp>

#include <spdlog/logger.h>

#include <chrono>
#include <memory>

namespace medax::detail {

/// The stage's generator seed: the pipeline seed mixed with the stage id (SplitMix64).
std::uint64_t stage_seed(std::uint64_t pipeline_seed, const std::string& stage_id);

/// Installs a SIGINT and SIGTERM handler that asks running stages to stop (the runner then
/// stops cleanly and `medax` exits 128 + the signal: 130, 143); a second signal exits at once.
void install_interrupt_handler();
bool interrupt_requested();
/// The first SIGINT/SIGTERM received since the handler was installed; 0 if none. Exported
/// for the CLI's exit code (declared again in framework/cli/commands.hpp).
int interrupt_signal();
/// "SIGINT (Ctrl-C)", "SIGTERM", for log lines and messages.
std::string signal_name(int sig);

class RunContext : public Context {
 public:
  RunContext(std::shared_ptr<spdlog::logger> logger, std::string stage_id, std::uint64_t seed,
             std::filesystem::path out_dir, SceneData& data);
  ~RunContext() override;

  void info(std::string_view message) override;
  void warn(std::string_view message) override;
  void progress(double fraction, std::string_view what) override;
  bool cancelled() const override { return interrupt_requested(); }
  std::mt19937_64& rng() override { return rng_; }
  std::uint64_t seed() const override { return seed_; }
  std::filesystem::path write_output(const std::string& name,
                                     const std::function<void(std::ostream&)>& body) override;
  const std::string& stage_id() const override { return stage_id_; }
  SceneData& data() override { return data_; }

 private:
  std::shared_ptr<spdlog::logger> logger_;
  std::string stage_id_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;
  std::filesystem::path out_dir_;
  std::chrono::steady_clock::time_point last_progress_;
  bool progress_shown_ = false;
  bool terminal_;
  SceneData& data_;
};

}  // namespace medax::detail
