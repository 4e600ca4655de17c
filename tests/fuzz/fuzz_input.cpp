// Feeding fuzz inputs to medax's readers. Pipelines are validated against a registry of small
// in-process stages (one per parameter kind and role), so no plugin library is loaded.
#include "fuzz_input.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/plugin.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace medax::fuzz {

namespace fs = std::filesystem;

namespace {

class FuzzScale : public ConditioningStage {
 public:
  static StageInfo describe() { return {"fuzz_scale", "Scale (fuzz stage)", ""}; }
  void declare(ParamBinder& p) override {
    p.add("factor", factor_, "scale factor").range(0.001, 1000);
    p.add("axis", axis_, {"x", "y", "z"}, "axis");
  }
  void condition(Shape&, Context&) override {}

 private:
  double factor_ = 1.0;
  std::string axis_ = "x";
};

class FuzzField : public SignificanceStage {
 public:
  static StageInfo describe() { return {"fuzz_field", "A vertex field (fuzz stage)", ""}; }
  void declare(ParamBinder& p) override {
    p.add("factor", factor_, "multiplier").at_least(0);
    p.add("field", field_, "name of the field");
  }
  void check_params() const override {
    if (field_.empty()) throw std::invalid_argument("`field` must name the field");
  }
  void measure(const Shape&, MedialComplex&, Context&) override {}

 private:
  double factor_ = 2.0;
  std::string field_ = "f";
};

class FuzzExtract : public ExtractionStage {
 public:
  static StageInfo describe() { return {"fuzz_extract", "Extraction (fuzz stage)", ""}; }
  void declare(ParamBinder& p) override {
    p.add("samples", samples_, "sample count").range(1, 1e6);
    p.add("exact", exact_, "exact arithmetic");
    p.add("oracle", oracle_, "fuzz_field", "significance oracle");
  }
  MedialComplex extract(const Shape&, Context&) override { return {}; }

 private:
  int samples_ = 10;
  bool exact_ = false;
  StageSlot<SignificanceStage> oracle_;
};

class FuzzCount : public EvaluationStage {
 public:
  static StageInfo describe() { return {"fuzz_count", "Counts (fuzz stage)", ""}; }
  void declare(ParamBinder& p) override { p.add("seed", seed_, "a whole number"); }
  Metrics evaluate(const Shape&, const MedialComplex&, Context&) override { return {}; }

 private:
  long long seed_ = 0;
};

const Registry& fuzz_registry() {
  static Registry* registry = [] {
    auto* r = new Registry();
    PluginRegistrar stages;
    stages.add<FuzzScale>();
    stages.add<FuzzField>();
    stages.add<FuzzExtract>();
    stages.add<FuzzCount>();
    r->add_package({"fuzz", "1", {}}, stages);
    return r;
  }();
  return *registry;
}

/// A folder of this process in /dev/shm (tmpfs: no disk traffic per input), with the small
/// mesh `cube.off` that pipeline inputs may name.
const fs::path& scratch() {
  static const fs::path dir = [] {
    const fs::path d = fs::path("/dev/shm") / ("medax-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::ofstream(d / "cube.off") << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    return d;
  }();
  return dir;
}

fs::path write_input(std::string_view target, std::string_view bytes) {
  std::string ext = std::string(target.substr(0, target.find('_')));
  if (ext == "pipeline") ext = "yaml";
  const fs::path file = scratch() / ("input." + ext);
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return file;
}

}  // namespace

const std::vector<std::string>& targets() {
  static const std::vector<std::string> names{"off", "obj", "ply_ascii", "ply_binary", "stl", "ma", "pipeline", "xyz"};
  return names;
}

bool feed(std::string_view target, std::string_view bytes) {
  const fs::path file = write_input(target, bytes);
  try {
    if (target == "ma") read_ma(file);
    else if (target == "pipeline") load_pipeline(file, fuzz_registry());
    else if (target == "xyz") read_point_set(file);
    else read_shape(file);  // a mesh, or for a file without faces a point set
    return true;
  } catch (const IoError&) {
    return false;
  } catch (const PipelineError&) {
    return false;
  }
}

}  // namespace medax::fuzz
