// A stage as a parameter of another stage (Durix's extractor calls a significance oracle):
// short and long forms, defaults, role checks, and the nested instance actually used.
#include "kernel_test_support.hpp"

#include <medax/kernel/pipeline.hpp>

using namespace medax;
using medax::test::data_file;
using medax::test::pipeline_errors;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace {

PipelineConfig load_oracle_pipeline(const std::string& name, const std::string& oracle_yaml) {
  std::string yaml = "input: " + data_file("cube.off") + "\nstages:\n  - plugin: test_oracle_centroid\n";
  if (!oracle_yaml.empty()) yaml += "    params:\n      oracle: " + oracle_yaml + "\n";
  return load_pipeline(write_text(scratch_dir(name) / "p.yaml", yaml), medax::test::good_registry());
}

}  // namespace

TEST_CASE("a nested stage given in long form gets its parameters and defaults", "[pipeline][nested]") {
  const auto config = load_oracle_pipeline("nested_long", "{plugin: test_radius_field, params: {factor: 3}}");
  const StageRef& ref = config.stages[0].params.stage_ref("oracle");
  CHECK(ref.plugin == "test_radius_field");
  CHECK(ref.params.real("factor") == 3.0);
  CHECK(ref.params.text("field") == "radius_times");  // default filled in
  REQUIRE(ref.instance);
  CHECK(medax::test::bound_value(*ref.instance, "factor") == "3");
}

TEST_CASE("a nested stage given by name alone takes its defaults", "[pipeline][nested]") {
  const auto config = load_oracle_pipeline("nested_short", "test_radius_field");
  CHECK(config.stages[0].params.stage_ref("oracle").params.real("factor") == 2.0);
}

TEST_CASE("an omitted stage parameter uses the declared default stage", "[pipeline][nested]") {
  const auto config = load_oracle_pipeline("nested_default", "");
  const StageRef& ref = config.stages[0].params.stage_ref("oracle");
  CHECK(ref.plugin == "test_radius_field");
  CHECK(ref.params.real("factor") == 2.0);
}

TEST_CASE("the configured nested stage is the one the outer stage calls", "[pipeline][nested]") {
  const auto config = load_oracle_pipeline("nested_call", "{plugin: test_radius_field, params: {factor: 3, field: f}}");
  auto& extraction = dynamic_cast<ExtractionStage&>(*config.stages[0].instance);
  Shape shape;
  shape.mesh.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 2, 0), Vec3(0, -2, 0)};
  BasicContext ctx;
  const MedialComplex medial = extraction.extract(shape, ctx);
  REQUIRE(medial.num_vertices() == 1);
  CHECK(medial.radii[0] == Approx(1.5));
  REQUIRE(medial.vertex_props.fields.has("f"));
  CHECK(medial.vertex_props.fields.get("f")[0] == Approx(4.5));
}

TEST_CASE("a nested stage of the wrong role is reported at its plugin name", "[pipeline][nested]") {
  const auto dir = scratch_dir("nested_wrong_role");
  const std::string yaml = "input: " + data_file("cube.off") +
                           "\nstages:\n  - plugin: test_oracle_centroid\n    params:\n      oracle: {plugin: test_count}\n";
  const auto diagnostics = pipeline_errors(dir, yaml);
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].line == 5);
  CHECK(diagnostics[0].column == 24);
  CHECK_THAT(diagnostics[0].message,
             Catch::Contains("'test_count' is an evaluation stage but this parameter needs a significance stage"));
}

TEST_CASE("errors inside a nested stage carry their own positions", "[pipeline][nested]") {
  const auto dir = scratch_dir("nested_bad_param");
  const std::string yaml = "input: " + data_file("cube.off") +
                           "\nstages:\n  - plugin: test_oracle_centroid\n    params:\n      oracle:\n"
                           "        plugin: test_radius_fild\n";
  const auto diagnostics = pipeline_errors(dir, yaml);
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].line == 6);
  CHECK(diagnostics[0].column == 17);
  CHECK_THAT(diagnostics[0].message, Catch::Contains("did you mean 'test_radius_field'"));

  const auto range = pipeline_errors(dir, "input: " + data_file("cube.off") +
                                              "\nstages:\n  - plugin: test_oracle_centroid\n    params:\n"
                                              "      oracle: {plugin: test_radius_field, params: {factor: -1}}\n");
  REQUIRE(range.size() == 1);
  CHECK(range[0].line == 5);
  CHECK_THAT(range[0].message, Catch::Contains("parameter 'factor' of 'test_radius_field' is -1 but must be >= 0"));
}
