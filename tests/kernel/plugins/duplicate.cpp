// A package that registers `test_centroid` again (already offered by the good package) and one
// stage of its own.
#include <medax/plugin.hpp>

namespace {

using namespace medax;

class DuplicateCentroid : public ExtractionStage {
 public:
  static StageInfo describe() { return {"test_centroid", "A second stage with a taken name", "", {}}; }
  MedialComplex extract(const Shape&, Context&) override { return {}; }
};

class DuplicateOwn : public EvaluationStage {
 public:
  static StageInfo describe() { return {"test_duplicate_own", "A stage only this package offers", "", {}}; }
  Metrics evaluate(const Shape&, const MedialComplex& medial, Context&) override {
    return {{"radius_sum", [&] { double s = 0; for (double r : medial.radii) s += r; return s; }()}};
  }
};

}  // namespace

MEDAX_PLUGIN("kernel_test_duplicate", "0.1.0") {
  registrar.add<DuplicateCentroid>();
  registrar.add<DuplicateOwn>();
}
