// The good test package: one small, real stage per role the kernel tests need, plus a stage
// that fails on purpose and one that takes another stage as a parameter.
#include <medax/plugin.hpp>

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
    return {"test_scale", "Scale the shape about the origin (kernel test stage)", "",
            {ParamSpec::real("factor", 1.0, "scale factor").range(0.001, 1000)}};
  }
  void condition(Shape& shape, Context&) override {
    const double f = params().real("factor");
    for (Vec3& v : shape.mesh.vertices) v *= f;
    for (Vec3& p : shape.samples.points) p *= f;
    shape.to_input = shape.to_input.after(Similarity{1.0 / f, Vec3::Zero()});
  }
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
    return {"test_centroid", "One sphere at the vertex centroid (kernel test stage)", "", {}};
  }
  MedialComplex extract(const Shape& shape, Context&) override { return centroid_complex(shape); }
};

/// Extraction that calls a significance stage given as its `oracle` parameter.
class TestOracleCentroid : public ExtractionStage {
 public:
  static StageInfo describe() {
    return {"test_oracle_centroid", "Centroid sphere measured by a nested significance stage", "",
            {ParamSpec::stage("oracle", Role::Significance, "test_radius_field", "significance oracle")}};
  }
  MedialComplex extract(const Shape& shape, Context& ctx) override {
    MedialComplex medial = centroid_complex(shape);
    params().stage<SignificanceStage>("oracle").measure(shape, medial, ctx);
    return medial;
  }
};

/// A vertex field `field` = factor × radius.
class TestRadiusField : public SignificanceStage {
 public:
  static StageInfo describe() {
    return {"test_radius_field", "Vertex field factor × radius (kernel test stage)", "",
            {ParamSpec::real("factor", 2.0, "multiplier").at_least(0),
             ParamSpec::text("field", "radius_times", "name of the vertex field")}};
  }
  void check_params() const override {
    if (params().text("field").empty()) throw std::invalid_argument("`field` must name the field, e.g. radius_times");
  }
  void measure(const Shape&, MedialComplex& medial, Context&) override {
    auto& column = medial.vertex_props.fields.add(params().text("field"), medial.num_vertices());
    for (std::size_t i = 0; i < column.size(); ++i) column[i] = params().real("factor") * medial.radii[i];
  }
};

/// Element counts of the medial complex.
class TestCount : public EvaluationStage {
 public:
  static StageInfo describe() {
    return {"test_count", "Count medial elements (kernel test stage)", "",
            {ParamSpec::choice("element", "all", {"all", "vertices", "edges", "faces"}, "what to count"),
             ParamSpec::boolean("log", false, "log the counts and write them to counts.txt")}};
  }
  Metrics evaluate(const Shape&, const MedialComplex& medial, Context& ctx) override {
    const std::string& what = params().text("element");
    Metrics m;
    if (what == "all" || what == "vertices") m["vertices"] = static_cast<double>(medial.num_vertices());
    if (what == "all" || what == "edges") m["edges"] = static_cast<double>(medial.edges.size());
    if (what == "all" || what == "faces") m["faces"] = static_cast<double>(medial.faces.size());
    if (params().boolean("log")) {
      ctx.info("counted " + what);
      ctx.write_output("counts.txt", [&](std::ostream& out) {
        for (const auto& [name, value] : m) out << name << ' ' << value << '\n';
      });
    }
    return m;
  }
};

/// Draws from the stage's RNG stream: `first` is the first 53-bit draw (exact as a double).
class TestRandom : public EvaluationStage {
 public:
  static StageInfo describe() {
    return {"test_random", "Report draws from the stage RNG (kernel test stage)", "",
            {ParamSpec::integer("draws", 3, "uniform draws averaged into `mean`").range(1, 1000)}};
  }
  Metrics evaluate(const Shape&, const MedialComplex&, Context& ctx) override {
    Metrics m;
    m["first"] = static_cast<double>(ctx.rng()() >> 11);
    double sum = 0;
    const long long n = params().integer("draws");
    for (long long i = 0; i < n; ++i) sum += std::generate_canonical<double, 53>(ctx.rng());
    m["mean"] = sum / static_cast<double>(n);
    return m;
  }
};

/// Damages the complex, then throws: the run must stop and keep the state before this stage.
class TestFail : public SimplificationStage {
 public:
  static StageInfo describe() {
    return {"test_fail", "Always fails (kernel test stage)", "",
            {ParamSpec::text("message", "test_fail failed on purpose", "the error message")}};
  }
  void simplify(const Shape&, MedialComplex& medial, Context&) override {
    for (double& r : medial.radii) r *= 100;
    throw std::runtime_error(params().text("message"));
  }
};

}  // namespace

MEDAX_PLUGIN("kernel_test", "1.2.3") {
  registrar.add<TestScale>();
  registrar.add<TestCentroid>();
  registrar.add<TestOracleCentroid>();
  registrar.add<TestRadiusField>();
  registrar.add<TestCount>();
  registrar.add<TestRandom>();
  registrar.add<TestFail>();
}
