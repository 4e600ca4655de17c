#pragma once
// What the kernel gives a running stage: logging, progress, a seeded RNG, cancellation, and a
// place to write extra outputs.
#include <medax/scene_data.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>

namespace medax {

/// Thrown by Context::check_cancelled() when the user interrupts the run.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled by the user") {}
};

class Context {
 public:
  virtual ~Context();

  virtual void info(std::string_view message) = 0;
  virtual void warn(std::string_view message) = 0;
  /// Reports progress of long work, `fraction` in [0, 1]. Cheap to call often: the kernel
  /// rate-limits what it prints.
  virtual void progress(double fraction, std::string_view what = {}) = 0;

  /// True once the user asked to stop (Ctrl-C). Long loops should call check_cancelled().
  virtual bool cancelled() const = 0;
  void check_cancelled() const {
    if (cancelled()) throw Cancelled();
  }

  /// The stage's own generator, seeded from the pipeline seed and the stage id: the same
  /// config and seed give the same stream, whatever other stages draw.
  virtual std::mt19937_64& rng() = 0;
  virtual std::uint64_t seed() const = 0;

  /// Writes an extra output file `name` into the run folder atomically (temp file + rename).
  /// Returns the final path. Without a run folder (library use) the call is a no-op.
  virtual std::filesystem::path write_output(const std::string& name,
                                             const std::function<void(std::ostream&)>& body) = 0;

  /// The id of the running stage (its plugin name unless the pipeline gives `id`).
  virtual const std::string& stage_id() const = 0;
  /// The scene's typed data (scene_data.hpp): what earlier stages published, and where this
  /// stage publishes its own.
  virtual SceneData& data() = 0;
  /// Publishes `value` under `key` as this stage.
  template <typename T>
  void publish(const DataKey<T>& key, T value) {
    data().publish(key, std::move(value), stage_id());
  }
};

/// A context for using stages from C++ directly (tests, scripts): logs to stderr when
/// `verbose`, never cancels, writes no outputs, keeps its own scene data.
class BasicContext : public Context {
 public:
  explicit BasicContext(std::uint64_t seed = 0, bool verbose = false, std::string stage_id = "stage");
  void info(std::string_view message) override;
  void warn(std::string_view message) override;
  void progress(double, std::string_view) override {}
  bool cancelled() const override { return false; }
  std::mt19937_64& rng() override { return rng_; }
  std::uint64_t seed() const override { return seed_; }
  std::filesystem::path write_output(const std::string&,
                                     const std::function<void(std::ostream&)>&) override {
    return {};
  }
  const std::string& stage_id() const override { return stage_id_; }
  SceneData& data() override { return data_; }

 private:
  std::uint64_t seed_;
  bool verbose_;
  std::mt19937_64 rng_;
  std::string stage_id_;
  SceneData data_;
};

}  // namespace medax
