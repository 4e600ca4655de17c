// Parameters declared once: a binding gives the declaration (`medax describe`), the default
// (the field's initial value) and the place where the validated value goes.
#include <medax/plugin.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace medax;

namespace {

enum class Mode { Fast, Exact };

struct Options {
  double epsilon = 0.01;
  int iterations = 10;
  std::size_t budget = 1000;
  double limit = INFINITY;
  bool flag = true;
  std::string name = "abc";
  Mode mode = Mode::Exact;
  std::string kind = "b";
};

struct Probe : SignificanceStage {
  static StageInfo describe() { return {"probe", "a probe", "docs/probe.md"}; }
  void measure(const Shape&, MedialComplex&, Context&) override {}
};

struct Declaring : EvaluationStage {
  static StageInfo describe() { return {"declaring", "declares one of each", ""}; }
  void declare(ParamBinder& p) override {
    p.add("epsilon", options.epsilon, "tolerance").range(0, 1).in_unit("bbox");
    p.add("iterations", options.iterations, "count").at_least(1);
    p.add("budget", options.budget, "size");
    p.add("limit", options.limit, "no limit");
    p.add("flag", options.flag, "a flag");
    p.add("name", options.name, "a name");
    p.add("mode", options.mode, {{"fast", Mode::Fast}, {"exact", Mode::Exact}}, "how");
    p.add("kind", options.kind, {"a", "b"}, "which");
    p.add("oracle", oracle, "probe", "a nested stage");
  }
  Metrics evaluate(const Shape&, const MedialComplex&, Context&) override { return {}; }
  Options options;
  StageSlot<SignificanceStage> oracle;
};

const ParamSpec& spec(const std::vector<ParamSpec>& specs, const std::string& name) {
  for (const ParamSpec& s : specs)
    if (s.name == name) return s;
  FAIL("no parameter " << name);
  throw;
}

}  // namespace

TEST_CASE("a binding declares type, default (the field's value), range and unit", "[params]") {
  const StageInfo info = stage_info<Declaring>();
  CHECK(info.name == "declaring");
  CHECK(info.role == Role::Evaluation);
  REQUIRE(info.params.size() == 9);
  CHECK(info.params[0].name == "epsilon");  // in declaration order

  const ParamSpec& eps = spec(info.params, "epsilon");
  CHECK(eps.type == ParamType::Real);
  CHECK(std::get<double>(eps.default_value) == 0.01);
  CHECK(eps.default_text() == "0.01");
  CHECK(eps.range_text() == "[0, 1]");
  CHECK(eps.unit == "bbox");

  const ParamSpec& n = spec(info.params, "iterations");
  CHECK(n.type == ParamType::Int);
  CHECK(n.default_text() == "10");
  CHECK(n.range_text() == ">= 1");
  CHECK(spec(info.params, "budget").type == ParamType::Int);

  CHECK(spec(info.params, "limit").default_text() == "inf");
  CHECK(spec(info.params, "limit").range_text().empty());
  CHECK(spec(info.params, "flag").default_text() == "true");
  CHECK(spec(info.params, "name").type == ParamType::String);
  CHECK(spec(info.params, "name").default_text() == "abc");

  const ParamSpec& mode = spec(info.params, "mode");
  CHECK(mode.type == ParamType::Choice);
  CHECK(mode.default_text() == "exact");  // the enum value's name
  CHECK(mode.range_text() == "one of fast|exact");
  CHECK(spec(info.params, "kind").default_text() == "b");

  const ParamSpec& oracle = spec(info.params, "oracle");
  CHECK(oracle.type == ParamType::Stage);
  CHECK(oracle.default_text() == "probe");
  CHECK(oracle.stage_role == Role::Significance);  // from the slot's type
  CHECK(oracle.range_text() == "a significance stage");
}

TEST_CASE("configure writes each given value into its field and leaves the others", "[params]") {
  Declaring stage;
  ParamSet values;
  values.set("epsilon", 0.5);
  values.set("iterations", 7LL);
  values.set("budget", 12LL);
  values.set("flag", false);
  values.set("mode", std::string("fast"));
  values.set("kind", std::string("a"));
  stage.configure(values);
  CHECK(stage.options.epsilon == 0.5);
  CHECK(stage.options.iterations == 7);
  CHECK(stage.options.budget == 12u);
  CHECK_FALSE(stage.options.flag);
  CHECK(stage.options.mode == Mode::Fast);
  CHECK(stage.options.kind == "a");
  CHECK(stage.options.name == "abc");  // not given: the default stays
  CHECK(std::isinf(stage.options.limit));

  ParamSet whole;
  whole.set("limit", 3LL);  // a whole number given for a real
  stage.configure(whole);
  CHECK(stage.options.limit == 3.0);

  ParamSet not_a_choice;
  not_a_choice.set("mode", std::string("slow"));
  CHECK_THROWS_WITH(stage.configure(not_a_choice), Catch::Contains("'slow' is not one of"));
  not_a_choice.set("mode", std::string("fast"));
  not_a_choice.set("kind", std::string("z"));
  CHECK_THROWS_WITH(stage.configure(not_a_choice), Catch::Contains("'z' is not one of"));

  ParamSet unknown;
  unknown.set("nope", 1.0);
  CHECK_THROWS_WITH(stage.configure(unknown), Catch::Contains("no parameter named 'nope'"));
}

TEST_CASE("a stage slot holds the nested stage, typed by its role", "[params]") {
  Declaring stage;
  CHECK(stage.oracle.empty());
  CHECK(stage.oracle.find() == nullptr);
  CHECK_THROWS(stage.oracle.get());
  auto ref = std::make_shared<StageRef>();
  ref->plugin = "probe";
  ref->instance = std::make_shared<Probe>();
  ParamSet values;
  values.set("oracle", ref);
  stage.configure(values);
  CHECK(&stage.oracle.get() == ref->instance.get());
  CHECK(stage.oracle.plugin() == "probe");

  CHECK(stage.oracle.find() == ref->instance.get());
  StageSlot<EvaluationStage> wrong;
  wrong.set(ref);
  CHECK(wrong.find() == nullptr);
  CHECK_THROWS_WITH(wrong.get(), Catch::Contains("'probe' is not of the kind"));
}

TEST_CASE("a parameter declared twice or a choice default not among the choices is refused", "[params]") {
  double x = 1;
  std::string s = "c";
  ParamBinder binder;
  binder.add("x", x, "");
  CHECK_THROWS_WITH(binder.add("x", x, ""), Catch::Contains("declared twice"));
  CHECK_THROWS_WITH(binder.add("s", s, {"a", "b"}, ""), Catch::Contains("not one of its choices"));
}

TEST_CASE("ParamSet gives typed values of the resolved config and refuses the wrong type", "[params]") {
  ParamSet set;
  set.set("flag", true);
  set.set("count", 7LL);
  set.set("ratio", 0.5);
  set.set("name", std::string("abc"));
  CHECK(set.boolean("flag"));
  CHECK(set.integer("count") == 7);
  CHECK(set.real("count") == 7.0);  // an Int reads as a real
  CHECK(set.real("ratio") == 0.5);
  CHECK(set.text("name") == "abc");
  CHECK(set.has("ratio"));
  CHECK_FALSE(set.has("missing"));
  CHECK_THROWS_AS(set.at("missing"), std::out_of_range);
  CHECK_THROWS_WITH(set.integer("ratio"), Catch::Contains("not of type int"));
  CHECK_THROWS_WITH(set.text("count"), Catch::Contains("not of type string"));
  CHECK_THROWS(set.stage_ref("name"));
}
