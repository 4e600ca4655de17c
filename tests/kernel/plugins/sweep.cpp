// Stages that misbehave on purpose, for the sweep runner's isolation tests.
#include <medax/medax.hpp>

#include <chrono>
#include <cstdlib>
#include <thread>

using namespace medax;

namespace {

/// Aborts the process when `crash` is true (a segfault-like failure of one job).
class TestCrash : public EvaluationStage {
 public:
  static StageInfo describe() {
    return {"test_crash", "Abort the process when asked (sweep test stage)", ""};
  }
  void declare(ParamBinder& p) override { p.add("crash", crash_, "call std::abort"); }
  Metrics evaluate(const Shape&, const MedialComplex&, Context&) override {
    if (crash_) std::abort();
    return {{"survived", 1.0}};
  }

 private:
  bool crash_ = false;
};

/// Sleeps, so a job can outlive its time limit.
class TestSleep : public EvaluationStage {
 public:
  static StageInfo describe() {
    return {"test_sleep", "Sleep for a while (sweep test stage)", ""};
  }
  void declare(ParamBinder& p) override { p.add("seconds", seconds_, "how long to sleep").range(0, 3600).in_unit("s"); }
  Metrics evaluate(const Shape&, const MedialComplex&, Context&) override {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds_));
    return {{"slept", seconds_}};
  }

 private:
  double seconds_ = 0.0;
};

}  // namespace

MEDAX_PLUGIN("kernel_test_sweep", "1.0.0") {
  registrar.add<TestCrash>();
  registrar.add<TestSleep>();
}
