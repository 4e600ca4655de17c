// Command-line overrides (--set STAGE.PARAM=VALUE, --input): applied before validation, errors
// attributed to the option that caused them.
#include "kernel_test_support.hpp"

#include <medax/kernel/pipeline.hpp>

using namespace medax;
using medax::test::data_file;
using medax::test::pipeline_errors;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace {

const std::string kPipeline = "input: " + data_file("cube.off") +
                              "\nstages:\n  - plugin: test_scale\n    params: {factor: 2}\n"
                              "  - {plugin: test_centroid, id: extract}\n  - plugin: test_count\n";

Diagnostic single_error(const std::string& dir_name, const std::vector<std::string>& settings) {
  const auto diagnostics = pipeline_errors(scratch_dir(dir_name), kPipeline, Overrides{{}, settings});
  for (const Diagnostic& d : diagnostics) UNSCOPED_INFO(d.format());
  REQUIRE(diagnostics.size() == 1);
  return diagnostics[0];
}

}  // namespace

TEST_CASE("override --set changes a given or a default parameter", "[pipeline][overrides]") {
  const auto file = write_text(scratch_dir("overrides_valid") / "p.yaml", kPipeline);
  const PipelineConfig plain = load_pipeline(file, medax::test::good_registry());
  CHECK(plain.stages[0].params.real("factor") == 2.0);
  CHECK(plain.stages[2].params.text("element") == "all");

  const PipelineConfig changed = load_pipeline(file, medax::test::good_registry(),
                                               Overrides{{}, {"test_scale.factor=3.5", "test_count.element=edges"}});
  CHECK(changed.stages[0].params.real("factor") == 3.5);
  CHECK(changed.stages[2].params.text("element") == "edges");
  // The instance is configured with the overridden value too.
  CHECK(medax::test::bound_value(*changed.stages[0].instance, "factor") == "3.5");
}

TEST_CASE("override --set addresses a stage by its id not its plugin name", "[pipeline][overrides]") {
  const auto by_plugin = single_error("overrides_by_plugin", {"test_centroid.x=1"});
  CHECK_THAT(by_plugin.message, Catch::Contains("no stage with id 'test_centroid'"));
  const auto by_id = single_error("overrides_by_id", {"extract.x=1"});
  CHECK(by_id.file == "--set extract.x=1");
  CHECK_THAT(by_id.message, Catch::Contains("'test_centroid' has no parameter 'x'"));
}

TEST_CASE("override --set with an unknown stage id names the option", "[pipeline][overrides]") {
  const auto d = single_error("overrides_unknown_stage", {"test_scal.factor=3"});
  CHECK(d.file == "--set test_scal.factor=3");
  CHECK(d.line == 0);
  CHECK_THAT(d.message, Catch::Contains("no stage with id 'test_scal'"));
  CHECK_THAT(d.message, Catch::Contains("did you mean 'test_scale'"));
  CHECK(d.format() == "--set test_scal.factor=3: error: " + d.message);
}

TEST_CASE("override --set with a bad value is attributed to the option not the file", "[pipeline][overrides]") {
  SECTION("mistyped") {
    const auto d = single_error("overrides_bad_value", {"test_scale.factor=abc"});
    CHECK(d.file == "--set test_scale.factor=abc");
    CHECK(d.line == 0);
    CHECK_THAT(d.message, Catch::Contains("parameter 'factor' of 'test_scale' must be a number but is 'abc'"));
  }
  SECTION("out of range") {
    const auto d = single_error("overrides_out_of_range", {"test_scale.factor=0"});
    CHECK(d.file == "--set test_scale.factor=0");
    CHECK_THAT(d.message, Catch::Contains("must be [0.001, 1000]"));
  }
  SECTION("not YAML") {
    const auto d = single_error("overrides_not_yaml", {"test_scale.factor=[1"});
    CHECK(d.file == "--set test_scale.factor=[1");
    CHECK_THAT(d.message, Catch::Contains("not valid YAML"));
  }
}

TEST_CASE("override --set with an unknown parameter is attributed to the option", "[pipeline][overrides]") {
  const auto d = single_error("overrides_unknown_param", {"test_scale.factr=2"});
  CHECK(d.file == "--set test_scale.factr=2");
  CHECK_THAT(d.message, Catch::Contains("'test_scale' has no parameter 'factr'"));
  CHECK_THAT(d.message, Catch::Contains("did you mean 'factor'"));
}

TEST_CASE("override --set without STAGE.PARAM=VALUE explains the syntax", "[pipeline][overrides]") {
  const auto d = single_error("overrides_syntax", {"factor=2"});
  CHECK(d.file == "--set factor=2");
  CHECK_THAT(d.message, Catch::Contains("expected STAGE.PARAM=VALUE"));
}

TEST_CASE("override --input replaces the input and a missing one names the option", "[pipeline][overrides]") {
  const auto dir = scratch_dir("overrides_input");
  const auto file = write_text(dir / "p.yaml", kPipeline);
  const PipelineConfig config =
      load_pipeline(file, medax::test::good_registry(), Overrides{data_file("sphere.obj"), {}});
  CHECK(config.input == std::filesystem::path(data_file("sphere.obj")));

  const auto diagnostics = pipeline_errors(dir, kPipeline, Overrides{dir / "missing.off", {}});
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].file == "--input");
  CHECK_THAT(diagnostics[0].message, Catch::Contains("missing.off not found"));
}

TEST_CASE("a stage can be switched off in the file or with --set STAGE.enabled=false", "[pipeline]") {
  const auto dir = scratch_dir("overrides_enabled");
  const auto file = medax::test::write_text(
      dir / "pipeline.yaml", "input: " + data_file("cube.off") +
                                 "\nstages:\n  - {plugin: test_scale, id: scale, enabled: false}\n"
                                 "  - plugin: test_centroid\n  - {plugin: test_count, id: count}\n");
  const auto config = load_pipeline(file, medax::test::good_registry());
  REQUIRE(config.stages.size() == 2);
  CHECK(config.stages[0].plugin == "test_centroid");
  const auto fewer = load_pipeline(file, medax::test::good_registry(), Overrides{{}, {"count.enabled=false"}});
  CHECK(fewer.stages.size() == 1);
  const auto again = load_pipeline(file, medax::test::good_registry(), Overrides{{}, {"scale.enabled=true"}});
  CHECK(again.stages.size() == 3);
}
