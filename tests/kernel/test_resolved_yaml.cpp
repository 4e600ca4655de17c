// The resolved configuration: every default filled in, and reading it back reproduces it.
#include "kernel_test_support.hpp"

#include <medax/kernel/pipeline.hpp>

using namespace medax;
using medax::test::data_file;
using medax::test::scratch_dir;
using medax::test::write_text;

TEST_CASE("resolved_yaml fills in defaults and survives a round trip unchanged", "[pipeline][resolved]") {
  const auto dir = scratch_dir("resolved_round_trip");
  std::filesystem::copy_file(data_file("cube.off"), dir / "cube.off");
  // A relative input, nested stages in both forms, omitted parameters, a string with YAML
  // meaning and a real given as an integer.
  const auto file = write_text(dir / "original.yaml",
                               "name: round trip\n"
                               "seed: 7\n"
                               "input: cube.off\n"
                               "stages:\n"
                               "  - plugin: test_scale\n"
                               "    params: {factor: 3}\n"
                               "  - plugin: test_oracle_centroid\n"
                               "    params:\n"
                               "      oracle: {plugin: test_radius_field, params: {field: 'yes: no'}}\n"
                               "  - {plugin: test_count, id: count}\n"
                               "  - plugin: test_random\n"
                               "outputs: {medial: [ma, obj], surface: off, frame: working}\n");
  const PipelineConfig first = load_pipeline(file, medax::test::good_registry());
  const std::string resolved = resolved_yaml(first);
  INFO(resolved);

  // Defaults and normalised values are written out.
  CHECK_THAT(resolved, Catch::Contains("factor: 3.0"));
  CHECK_THAT(resolved, Catch::Contains("factor: 2.0"));  // the nested stage's default
  CHECK_THAT(resolved, Catch::Contains("\"yes: no\""));
  CHECK_THAT(resolved, Catch::Contains("element: \"all\""));
  CHECK_THAT(resolved, Catch::Contains("log: false"));
  CHECK_THAT(resolved, Catch::Contains("draws: 3"));
  CHECK_THAT(resolved, Catch::Contains("id: count"));
  CHECK_THAT(resolved, Catch::Contains("seed: 7"));
  CHECK_THAT(resolved, Catch::Contains("input: " + (dir / "cube.off").string()));  // absolute
  CHECK_THAT(resolved, Catch::Contains("frame: working"));

  // Written elsewhere and read back, it gives the same configuration and the same text.
  const auto other_dir = scratch_dir("resolved_round_trip_copy");
  const PipelineConfig second = load_pipeline(write_text(other_dir / "config.resolved.yaml", resolved),
                                              medax::test::good_registry());
  CHECK(resolved_yaml(second) == resolved);
  CHECK(second.name == "round trip");
  CHECK(second.seed == 7);
  CHECK(second.input == dir / "cube.off");
  REQUIRE(second.stages.size() == 4);
  CHECK(second.stages[1].params.stage_ref("oracle").params.text("field") == "yes: no");
  CHECK(second.outputs.medial == std::vector<std::string>{"ma", "obj"});
  CHECK(second.outputs.surface == std::vector<std::string>{"off"});
  CHECK_FALSE(second.outputs.input_frame);
}

TEST_CASE("resolved_yaml keeps reals exact", "[pipeline][resolved]") {
  const auto dir = scratch_dir("resolved_exact_reals");
  const auto file = write_text(dir / "p.yaml", "input: " + data_file("cube.off") +
                                                   "\nstages:\n  - plugin: test_scale\n"
                                                   "    params: {factor: 2.71828182845904523536028747135}\n");
  const PipelineConfig first = load_pipeline(file, medax::test::good_registry());
  const std::string resolved = resolved_yaml(first);
  CHECK_THAT(resolved, Catch::Contains("factor: 2.718281828459045\n"));  // shortest exact text
  const PipelineConfig second = load_pipeline(write_text(dir / "r.yaml", resolved), medax::test::good_registry());
  CHECK(second.stages[0].params.real("factor") == first.stages[0].params.real("factor"));
}
