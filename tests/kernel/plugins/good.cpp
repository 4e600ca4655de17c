// The good test package: one small, real stage per role the kernel tests need, plus a stage
// that fails on purpose and one that takes another stage as a parameter.
#include <medax/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <random>
#include <stdexcept>

namespace {

using namespace medax;

/// Scales the shape about the origin and records the map back to the input frame.
class TestScale : public ConditioningStage {
 public:
  static StageInfo describe() {
    return {"test_scale", "Scale the shape about the origin (kernel test stage)", ""};
  }
  void declare(ParamBinder& p) override {
    p.add("factor", factor_, "scale factor").range(0.001, 1000);
    p.add("sample", sample_, "then take the vertices as the shape's samples");
  }
  void condition(Shape& shape, Context&) override {
    const double f = factor_;
    for (Vec3& v : shape.mesh.vertices) v *= f;
    for (Vec3& p : shape.samples.points) p *= f;
    shape.to_input = shape.to_input.after(Similarity{1.0 / f, Vec3::Zero()});
    if (sample_) shape.samples.points = shape.mesh.vertices;
  }
  std::vector<ShapePart> makes() const override {
    if (sample_) return {ShapePart::Samples};
    return {};
  }

 private:
  double factor_ = 1.0;
  bool sample_ = false;
};

/// One medial vertex at the vertex centroid, radius the mean vertex distance to it.
MedialComplex centroid_complex(const Shape& shape) {
  const auto& vertices = shape.mesh.vertices;
  if (vertices.empty()) throw std::invalid_argument("the shape has no vertices");
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : vertices) centre += v;
  centre /= static_cast<double>(vertices.size());
  double radius = 0;
  for (const Vec3& v : vertices) radius += (v - centre).norm();
  MedialComplex medial;
  medial.add_vertex(centre, radius / static_cast<double>(vertices.size()));
  return medial;
}

class TestCentroid : public ExtractionStage {
 public:
  static StageInfo describe() {
    return {"test_centroid", "One sphere at the vertex centroid (kernel test stage)", ""};
  }
  void declare(ParamBinder& p) override {
    p.add("points", points_, {"vertices", "samples"}, "whose centroid: the mesh vertices or the samples");
  }
  MedialComplex extract(const Shape& shape, Context&) override {
    if (points_ == "vertices") return centroid_complex(shape);
    Shape of_samples;
    of_samples.mesh.vertices = shape.samples.points;
    return centroid_complex(of_samples);
  }
  std::vector<ShapePart> needs() const override {
    if (points_ == "samples") return {ShapePart::Samples};
    return {};
  }

 private:
  std::string points_ = "vertices";
};

/// Extraction that calls a significance stage given as its `oracle` parameter.
class TestOracleCentroid : public ExtractionStage {
 public:
  static StageInfo describe() {
    return {"test_oracle_centroid", "Centroid sphere measured by a nested significance stage", ""};
  }
  void declare(ParamBinder& p) override { p.add("oracle", oracle_, "test_radius_field", "significance oracle"); }
  MedialComplex extract(const Shape& shape, Context& ctx) override {
    MedialComplex medial = centroid_complex(shape);
    oracle_->measure(shape, medial, ctx);
    return medial;
  }

 private:
  StageSlot<SignificanceStage> oracle_;
};

/// A vertex field `field` = factor × radius.
class TestRadiusField : public SignificanceStage {
 public:
  static StageInfo describe() {
    return {"test_radius_field", "Vertex field factor × radius (kernel test stage)", ""};
  }
  void declare(ParamBinder& p) override {
    p.add("factor", factor_, "multiplier").at_least(0);
    p.add("field", field_, "name of the vertex field");
  }
  void check_params() const override {
    if (field_.empty()) throw std::invalid_argument("`field` must name the field, e.g. radius_times");
  }
  void measure(const Shape&, MedialComplex& medial, Context&) override {
    auto& column = medial.add(Property<double>{Element::Vertex, field_});
    for (std::size_t i = 0; i < column.size(); ++i) column[i] = factor_ * medial.radii[i];
  }

 private:
  double factor_ = 2.0;
  std::string field_ = "radius_times";
};

/// Element counts of the medial complex.
class TestCount : public EvaluationStage {
 public:
  static StageInfo describe() {
    return {"test_count", "Count medial elements (kernel test stage)", ""};
  }
  void declare(ParamBinder& p) override {
    p.add("element", element_, {"all", "vertices", "edges", "faces"}, "what to count");
    p.add("log", log_, "log the counts and write them to counts.txt");
  }
  Metrics evaluate(const Shape&, const MedialComplex& medial, Context& ctx) override {
    const std::string& what = element_;
    Metrics m;
    if (what == "all" || what == "vertices") m["vertices"] = static_cast<double>(medial.num_vertices());
    if (what == "all" || what == "edges") m["edges"] = static_cast<double>(medial.edges.size());
    if (what == "all" || what == "faces") m["faces"] = static_cast<double>(medial.faces.size());
    if (log_) {
      ctx.info("counted " + what);
      ctx.write_output("counts.txt", [&](std::ostream& out) {
        for (const auto& [name, value] : m) out << name << ' ' << value << '\n';
      });
    }
    return m;
  }

 private:
  std::string element_ = "all";
  bool log_ = false;
};

/// Draws from the stage's RNG stream: `first` is the first 53-bit draw (exact as a double).
class TestRandom : public EvaluationStage {
 public:
  static StageInfo describe() {
    return {"test_random", "Report draws from the stage RNG (kernel test stage)", ""};
  }
  void declare(ParamBinder& p) override { p.add("draws", draws_, "uniform draws averaged into `mean`").range(1, 1000); }
  Metrics evaluate(const Shape&, const MedialComplex&, Context& ctx) override {
    Metrics m;
    m["first"] = static_cast<double>(ctx.rng()() >> 11);
    double sum = 0;
    const long long n = draws_;
    for (long long i = 0; i < n; ++i) sum += std::generate_canonical<double, 53>(ctx.rng());
    m["mean"] = sum / static_cast<double>(n);
    return m;
  }

 private:
  long long draws_ = 3;
};

/// Damages the complex, then throws: the run must stop and keep the state before this stage.
class TestFail : public SimplificationStage {
 public:
  static StageInfo describe() {
    return {"test_fail", "Always fails (kernel test stage)", ""};
  }
  void declare(ParamBinder& p) override { p.add("message", message_, "the error message"); }
  void simplify(const Shape&, MedialComplex& medial, Context&) override {
    for (double& r : medial.radii) r *= 100;
    throw std::runtime_error(message_);
  }

 private:
  std::string message_ = "test_fail failed on purpose";
};

/// The largest radius, passed on as scene data (and written to <id>_largest_radius.txt).
const DataKey<double> kLargestRadius{"test.largest_radius", "test_publish", "largest_radius.txt",
                                     [](const double& r, std::ostream& out) { out << r << '\n'; }};

class TestPublish : public SignificanceStage {
 public:
  static StageInfo describe() { return {"test_publish", "Publish the largest radius (kernel test stage)", ""}; }
  void measure(const Shape&, MedialComplex& medial, Context& ctx) override {
    double largest = 0;
    for (double r : medial.radii) largest = std::max(largest, r);
    ctx.publish(kLargestRadius, largest);
  }
};

class TestConsume : public EvaluationStage {
 public:
  static StageInfo describe() { return {"test_consume", "Report the published largest radius (kernel test stage)", ""}; }
  Metrics evaluate(const Shape&, const MedialComplex&, Context& ctx) override {
    return {{"largest_radius", ctx.data().get(kLargestRadius)}};
  }
};

}  // namespace

MEDAX_PLUGIN("kernel_test", "1.2.3") {
  registrar.add<TestPublish>();
  registrar.add<TestConsume>();
  registrar.add<TestScale>();
  registrar.add<TestCentroid>();
  registrar.add<TestOracleCentroid>();
  registrar.add<TestRadiusField>();
  registrar.add<TestCount>();
  registrar.add<TestRandom>();
  registrar.add<TestFail>();
}
