// Parameter declarations (the text `medax describe` shows) and typed access to resolved values.
#include <medax/params.hpp>
#include <medax/stage.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace medax;

TEST_CASE("ParamSpec builders record type and default and range", "[params]") {
  const ParamSpec eps = ParamSpec::real("epsilon", 0.01, "tolerance").range(0, 1).in_unit("bbox");
  CHECK(eps.type == ParamType::Real);
  CHECK(std::get<double>(eps.default_value) == 0.01);
  CHECK(eps.default_text() == "0.01");
  CHECK(eps.range_text() == "[0, 1]");
  CHECK(eps.unit == "bbox");

  const ParamSpec n = ParamSpec::integer("iterations", 10, "count").at_least(1);
  CHECK(n.default_text() == "10");
  CHECK(n.range_text() == ">= 1");

  const ParamSpec big = ParamSpec::real("limit", INFINITY, "no limit");
  CHECK(big.default_text() == "inf");
  CHECK(big.range_text().empty());

  CHECK(ParamSpec::boolean("flag", true, "").default_text() == "true");
  CHECK(ParamSpec::text("name", "abc", "").default_text() == "abc");

  const ParamSpec mode = ParamSpec::choice("mode", "fast", {"fast", "exact"}, "");
  CHECK(mode.type == ParamType::Choice);
  CHECK(mode.range_text() == "one of fast|exact");

  const ParamSpec oracle = ParamSpec::stage("oracle", Role::Significance, "durix_epsilon", "");
  CHECK(oracle.type == ParamType::Stage);
  CHECK(oracle.default_text() == "durix_epsilon");
  CHECK(oracle.range_text() == "a significance stage");
}

TEST_CASE("ParamSet gives typed values and refuses the wrong type", "[params]") {
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

namespace {
struct Probe : SignificanceStage {
  static StageInfo describe() { return {"probe", "", "", {}}; }
  void measure(const Shape&, MedialComplex&, Context&) override {}
};
}  // namespace

TEST_CASE("ParamSet::stage casts a nested stage to its role interface", "[params]") {
  auto ref = std::make_shared<StageRef>();
  ref->plugin = "probe";
  ref->instance = std::make_shared<Probe>();
  ParamSet set;
  set.set("oracle", ref);
  CHECK(&set.stage<SignificanceStage>("oracle") == ref->instance.get());
  CHECK(set.stage_ref("oracle").plugin == "probe");
  CHECK_THROWS_WITH(set.stage<EvaluationStage>("oracle"), Catch::Contains("does not have the required role"));
}
