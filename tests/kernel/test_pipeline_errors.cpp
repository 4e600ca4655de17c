// Pipeline validation: every problem is reported before any work with file:line:column and
// what to do.
#include "kernel_test_support.hpp"

#include <medax/kernel/pipeline.hpp>

using namespace medax;
using medax::test::data_file;
using medax::test::pipeline_errors;
using medax::test::scratch_dir;

namespace {

/// A pipeline whose line 1 is a valid `input:`, so `body` starts on line 2.
std::string with_input(const std::string& body) { return "input: " + data_file("cube.off") + "\n" + body; }

struct Expected {
  int line, column;
  std::vector<std::string> fragments;
};

/// Asserts exactly one diagnostic, in `dir`/pipeline.yaml at the expected position.
void check_single(const std::filesystem::path& dir, const std::string& yaml, const Expected& expected) {
  INFO(yaml);
  const auto diagnostics = pipeline_errors(dir, yaml);
  for (const Diagnostic& d : diagnostics) UNSCOPED_INFO(d.format());
  REQUIRE(diagnostics.size() == 1);
  const Diagnostic& d = diagnostics[0];
  INFO(d.format());
  CHECK(d.file == (dir / "pipeline.yaml").string());
  CHECK(d.line == expected.line);
  CHECK(d.column == expected.column);
  for (const std::string& fragment : expected.fragments) CHECK_THAT(d.message, Catch::Contains(fragment));
}

}  // namespace

TEST_CASE("unknown plugin is reported at its name with the nearest names", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_unknown_plugin");
  check_single(dir, with_input("stages:\n  - plugin: test_centriod\n"),
               {3, 13, {"unknown plugin 'test_centriod'", "did you mean 'test_centroid'", "medax plugins"}});
  const auto d = pipeline_errors(dir, with_input("stages:\n  - plugin: test_centriod\n"));
  CHECK(d[0].format() == (dir / "pipeline.yaml").string() + ":3:13: error: " + d[0].message);
}

TEST_CASE("unknown parameter is reported at its key with the nearest parameter", "[pipeline]") {
  check_single(scratch_dir("pipeline_unknown_param"),
               with_input("stages:\n  - plugin: test_scale\n    params:\n      factr: 2\n"),
               {5, 7, {"'test_scale' has no parameter 'factr'", "did you mean 'factor'", "medax describe test_scale"}});
}

TEST_CASE("mistyped parameter values are reported at the value", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_mistyped");
  SECTION("a string for a real") {
    check_single(dir, with_input("stages:\n  - plugin: test_scale\n    params:\n      factor: big\n"),
                 {5, 15, {"parameter 'factor' of 'test_scale'", "must be a number", "'big'"}});
  }
  SECTION("a fraction for an int") {
    check_single(dir,
                 with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_random\n    params:\n"
                            "      draws: 2.5\n"),
                 {6, 14, {"parameter 'draws' of 'test_random'", "must be a whole number", "'2.5'"}});
  }
  SECTION("a word for a bool") {
    check_single(dir,
                 with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_count\n    params:\n"
                            "      log: maybe\n"),
                 {6, 12, {"parameter 'log' of 'test_count'", "must be true or false", "'maybe'"}});
  }
  SECTION("a list for a real") {
    check_single(dir, with_input("stages:\n  - plugin: test_scale\n    params:\n      factor: [1, 2]\n"),
                 {5, 15, {"parameter 'factor' of 'test_scale'", "must be a single real value"}});
  }
}

TEST_CASE("out-of-range parameter values are reported with the range", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_range");
  SECTION("real above its maximum") {
    check_single(dir, with_input("stages:\n  - plugin: test_scale\n    params:\n      factor: 5000\n"),
                 {5, 15, {"parameter 'factor' of 'test_scale' is 5000", "must be [0.001, 1000]"}});
  }
  SECTION("int below its minimum") {
    check_single(dir,
                 with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_random\n    params:\n"
                            "      draws: 0\n"),
                 {6, 14, {"parameter 'draws' of 'test_random' is 0", "must be [1, 1000]"}});
  }
}

TEST_CASE("a value outside a choice lists the choices and the nearest one", "[pipeline]") {
  check_single(scratch_dir("pipeline_choice"),
               with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_count\n    params:\n"
                          "      element: vertice\n"),
               {6, 16, {"is 'vertice'", "one of all|vertices|edges|faces", "did you mean 'vertices'"}});
}

TEST_CASE("a stage that needs a medial complex before any extraction is a role error", "[pipeline]") {
  check_single(scratch_dir("pipeline_role"), with_input("stages:\n  - plugin: test_count\n  - plugin: test_centroid\n"),
               {3, 5, {"'test_count' is an evaluation stage", "needs a medial complex",
                       "put an extraction stage before it"}});
}

TEST_CASE("a missing input file is reported at the input line", "[pipeline]") {
  check_single(scratch_dir("pipeline_missing_input"), "input: missing.off\nstages:\n  - plugin: test_centroid\n",
               {1, 8, {"missing.off not found", "relative to the pipeline file"}});
}

TEST_CASE("a pipeline without input names what to add", "[pipeline]") {
  const auto diagnostics = pipeline_errors(scratch_dir("pipeline_no_input"), "stages:\n  - plugin: test_centroid\n");
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].line == 0);
  CHECK_THAT(diagnostics[0].message, Catch::Contains("add `input: PATH`"));
}

TEST_CASE("text that is not YAML is reported with its position", "[pipeline]") {
  check_single(scratch_dir("pipeline_not_yaml"), "input: x.off\nstages: [test_centroid\nseed: 1\n",
               {3, 5, {"not valid YAML"}});
}

TEST_CASE("a pipeline that is not a map is rejected at its start", "[pipeline]") {
  check_single(scratch_dir("pipeline_not_map"), "- just\n- a list\n", {1, 1, {"a pipeline is a YAML map"}});
}

TEST_CASE("two stages with the same id are reported at the second", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_duplicate_ids");
  SECTION("implicit ids from the plugin name") {
    check_single(dir, with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_count\n  - plugin: test_count\n"),
                 {5, 5, {"two stages have the id 'test_count'", "give one of them `id: OTHER`"}});
  }
  SECTION("explicit ids") {
    check_single(dir,
                 with_input("stages:\n  - {plugin: test_centroid, id: a}\n  - {plugin: test_count, id: a}\n"),
                 {4, 5, {"two stages have the id 'a'"}});
  }
}

TEST_CASE("a key given twice in one map is reported at the second with the first's line", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_duplicate_keys");
  SECTION("a top-level `stages:` given twice (yaml-cpp alone keeps the first silently)") {
    check_single(dir, with_input("stages:\n  - plugin: test_centroid\nseed: 1\nstages:\n  - plugin: test_count\n"),
                 {5, 1, {"duplicate key 'stages'", "first at line 2", "remove one"}});
  }
  SECTION("a parameter given twice, in a flow map inside a stage") {
    check_single(dir,
                 with_input("stages:\n  - plugin: test_scale\n    params: {factor: 2, factor: 3}\n"
                            "  - plugin: test_centroid\n"),
                 {4, 25, {"duplicate key 'factor'", "first at line 4"}});
  }
  SECTION("each repeat is reported, in file order, alongside the other problems") {
    const auto diagnostics = pipeline_errors(
        dir, with_input("seed: 1\nstages:\n  - plugin: test_centroid\n    id: a\n    id: b\nseed: 2\nbogus: 1\n"));
    for (const Diagnostic& d : diagnostics) UNSCOPED_INFO(d.format());
    REQUIRE(diagnostics.size() == 3);
    CHECK(diagnostics[0].line == 6);
    CHECK_THAT(diagnostics[0].message, Catch::Contains("duplicate key 'id' (first at line 5)"));
    CHECK(diagnostics[1].line == 7);
    CHECK_THAT(diagnostics[1].message, Catch::Contains("duplicate key 'seed' (first at line 2)"));
    CHECK_THAT(diagnostics[2].message, Catch::Contains("unknown pipeline key 'bogus'"));
  }
  SECTION("the same key in different maps is not a duplicate") {
    const auto file = medax::test::write_text(
        dir / "pipeline.yaml",
        with_input("stages:\n  - {plugin: test_scale, id: a, params: {factor: 2}}\n"
                   "  - {plugin: test_scale, id: b, params: {factor: 3}}\n  - plugin: test_centroid\n"));
    CHECK(load_pipeline(file, medax::test::good_registry()).stages.size() == 3);
  }
}

TEST_CASE("unknown keys and formats are reported with the known ones", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_unknown_keys");
  SECTION("top-level key") {
    check_single(dir, with_input("stages:\n  - plugin: test_centroid\nsed: 3\n"),
                 {4, 1, {"unknown pipeline key 'sed'", "did you mean 'seed'"}});
  }
  SECTION("stage key") {
    check_single(dir, with_input("stages:\n  - plugin: test_centroid\n    parms: {}\n"),
                 {4, 5, {"unknown stage key 'parms'", "did you mean 'params'"}});
  }
  SECTION("output format") {
    check_single(dir, with_input("stages:\n  - plugin: test_centroid\noutputs:\n  medial: [ma, vtk]\n"),
                 {5, 16, {"unknown medial format 'vtk'", "ma, ply, obj"}});
  }
}

TEST_CASE("every problem in a pipeline is reported not only the first", "[pipeline]") {
  const auto diagnostics = pipeline_errors(
      scratch_dir("pipeline_many"),
      "input: missing.off\nseed: -4\nstages:\n  - plugin: test_scale\n    params: {factor: 0}\n  - plugin: nope\n");
  REQUIRE(diagnostics.size() == 4);
  CHECK(diagnostics[0].line == 2);  // seed
  CHECK(diagnostics[1].line == 1);  // input (checked after seed)
  CHECK(diagnostics[2].line == 5);  // factor out of range
  CHECK(diagnostics[3].line == 6);  // unknown plugin
}

TEST_CASE("a missing pipeline file is a PipelineError naming it", "[pipeline]") {
  const auto file = scratch_dir("pipeline_missing_file") / "nothing.yaml";
  try {
    load_pipeline(file, medax::test::good_registry());
    FAIL("no error");
  } catch (const PipelineError& e) {
    REQUIRE(e.diagnostics().size() == 1);
    CHECK(e.diagnostics()[0].file == file.string());
    CHECK_THAT(std::string(e.what()), Catch::Contains("no such pipeline file"));
  }
}

TEST_CASE("a valid pipeline loads with ids and roles and defaults and outputs", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_valid");
  const auto file = medax::test::write_text(
      dir / "p.yaml", with_input("seed: 42\nstages:\n  - plugin: test_scale\n  - {plugin: test_centroid, id: c}\n"
                                 "  - plugin: test_count\n    params: {element: faces}\n"));
  const PipelineConfig config = load_pipeline(file, medax::test::good_registry());
  CHECK(config.name == "p");
  CHECK(config.seed == 42);
  CHECK(config.input == std::filesystem::path(data_file("cube.off")));
  REQUIRE(config.stages.size() == 3);
  CHECK(config.stages[0].id == "test_scale");
  CHECK(config.stages[0].role == Role::Conditioning);
  CHECK(config.stages[0].params.real("factor") == 1.0);  // default filled in
  CHECK(config.stages[1].id == "c");
  CHECK(config.stages[1].instance->id() == "c");
  CHECK(config.stages[2].params.text("element") == "faces");
  CHECK(config.stages[2].params.boolean("log") == false);
  CHECK(config.outputs.medial == std::vector<std::string>{"ma", "ply"});  // the default outputs
}

TEST_CASE("malformed structure is always a PipelineError with a position", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_malformed");
  const std::vector<std::string> bodies{
      "name: [a, b]\nstages:\n  - plugin: test_centroid\n",
      "medax: {version: 1}\nstages:\n  - plugin: test_centroid\n",
      "seed: [1]\nstages:\n  - plugin: test_centroid\n",
      "stages: {plugin: test_centroid}\n",
      "stages:\n  - [test_centroid]\n",
      "stages:\n  - plugin: [test_centroid]\n",
      "stages:\n  - plugin: test_centroid\n    id: [x]\n",
      "stages:\n  - plugin: test_scale\n    params: [1, 2]\n",
      "stages:\n  - plugin: test_scale\n    params: {[factor]: 2}\n",
      "stages:\n  - {id: lonely}\n",
      "stages:\n  - plugin: test_centroid\noutputs: {frame: [input]}\n",
      "stages:\n  - plugin: test_centroid\noutputs: [ma]\n",
      "stages:\n  - plugin: test_centroid\noutputs: {medial: {ma: 1}}\n",
      "? [complex, key]\n: 1\nstages:\n  - plugin: test_centroid\n",
  };
  for (const std::string& body : bodies) {
    const std::string yaml = with_input(body);
    INFO(yaml);
    const auto diagnostics = pipeline_errors(dir, yaml);
    REQUIRE_FALSE(diagnostics.empty());
    for (const Diagnostic& d : diagnostics) {
      INFO(d.format());
      CHECK(d.line >= 2);
    }
  }
}

TEST_CASE("malformed --set targets are a PipelineError", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_malformed_set");
  const auto diagnostics = pipeline_errors(
      dir, with_input("stages:\n  - {plugin: test_centroid, id: [x]}\n  - plugin: {a: 1}\n  - 7\n"),
      Overrides{{}, {"x.y=1"}});
  CHECK_FALSE(diagnostics.empty());
}

TEST_CASE("a stage's own parameter check runs at validation and points at its params", "[pipeline]") {
  check_single(scratch_dir("pipeline_check_params"),
               with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_radius_field\n"
                          "    params: {field: \"\"}\n"),
               {5, 13, {"'test_radius_field'", "must name the field"}});
}

TEST_CASE("a stage that needs samples no earlier stage makes is refused at validation", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_shape_parts");
  // Without the check `validate` passed and `run` refused at once (voronoi with points: samples).
  check_single(dir, with_input("stages:\n  - plugin: test_centroid\n    params: {points: samples}\n"),
               {3, 5, {"'test_centroid' needs the shape's samples", "add one that does (e.g. `sample`) before it"}});
  const auto made_before = medax::test::write_text(
      dir / "made_before.yaml", with_input("stages:\n  - plugin: test_scale\n    params: {sample: true}\n"
                                           "  - plugin: test_centroid\n    params: {points: samples}\n"));
  CHECK_NOTHROW(load_pipeline(made_before, medax::test::good_registry()));
  CHECK_FALSE(pipeline_errors(dir, with_input("stages:\n  - plugin: test_centroid\n    params: {points: samples}\n"
                                              "  - plugin: test_scale\n    params: {sample: true}\n"))
                  .empty());
}

TEST_CASE("`medial_input:` and an extraction stage together are refused (the file would go unused)", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_medial_input_and_extraction");
  medax::test::write_text(dir / "given.ma", "1 0 0\nv 0.5 0.5 0.5 0.5\n");
  check_single(dir, with_input("medial_input: given.ma\nstages:\n  - plugin: test_centroid\n"),
               {4, 13, {"`test_centroid` (extraction) replaces the medial complex read from `medial_input:`",
                        "given.ma", "remove one of the two"}});
}

TEST_CASE("a conditioning stage after the medial complex exists is a role-order error at its plugin",
          "[pipeline]") {
  const auto dir = scratch_dir("pipeline_role_order");
  SECTION("after an extraction stage (normalize after voronoi gave an axis at twice the scale)") {
    check_single(dir,
                 with_input("stages:\n  - plugin: test_centroid\n  - plugin: test_scale\n    params: {factor: 2}\n"
                            "  - plugin: test_count\n"),
                 {4, 13, {"`test_scale` (conditioning) comes after `test_centroid` (extraction)",
                          "changes the shape but not the medial complex", "move it before the extraction"}});
  }
  SECTION("after `medial_input:`, which gives the complex before any stage") {
    medax::test::write_text(dir / "given.ma", "1 0 0\nv 0.5 0.5 0.5 0.5\n");
    check_single(dir,
                 with_input("medial_input: given.ma\nstages:\n  - plugin: test_scale\n  - plugin: test_count\n"),
                 {4, 13, {"`test_scale` (conditioning) comes after `medial_input:`", "given.ma",
                          "so the two would disagree"}});
  }
  SECTION("each late conditioning stage is reported, naming the first extraction") {
    const auto diagnostics =
        pipeline_errors(dir, with_input("stages:\n  - plugin: test_centroid\n  - {plugin: test_scale, id: a}\n"
                                        "  - {plugin: test_centroid, id: again}\n  - {plugin: test_scale, id: b}\n"));
    for (const Diagnostic& d : diagnostics) UNSCOPED_INFO(d.format());
    REQUIRE(diagnostics.size() == 2);
    CHECK(diagnostics[0].line == 4);
    CHECK(diagnostics[1].line == 6);
    for (const Diagnostic& d : diagnostics) CHECK_THAT(d.message, Catch::Contains("after `test_centroid`"));
  }
  SECTION("an invalid extraction stage still counts, so the late stage is reported too") {
    const auto diagnostics = pipeline_errors(
        dir, with_input("stages:\n  - {plugin: test_centroid, params: {nope: 1}}\n  - plugin: test_scale\n"));
    for (const Diagnostic& d : diagnostics) UNSCOPED_INFO(d.format());
    REQUIRE(diagnostics.size() == 2);
    CHECK(diagnostics[1].line == 4);
    CHECK_THAT(diagnostics[1].message, Catch::Contains("comes after `test_centroid` (extraction)"));
  }
}

TEST_CASE("conditioning before the extraction, or switched off after it, is valid", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_role_order_ok");
  const auto file = medax::test::write_text(
      dir / "pipeline.yaml",
      with_input("stages:\n  - {plugin: test_scale, id: a}\n  - plugin: test_centroid\n"
                 "  - {plugin: test_scale, id: late, enabled: false}\n  - plugin: test_count\n"));
  const PipelineConfig config = load_pipeline(file, medax::test::good_registry());
  REQUIRE(config.stages.size() == 3);
  CHECK(config.stages[0].id == "a");
  CHECK(config.stages[1].role == Role::Extraction);
  // Turned on from the command line, the late stage is refused like one written in the file.
  const auto diagnostics = pipeline_errors(
      dir, with_input("stages:\n  - plugin: test_centroid\n  - {plugin: test_scale, id: late, enabled: false}\n"),
      Overrides{{}, {"late.enabled=true"}});
  REQUIRE(diagnostics.size() == 1);
  CHECK_THAT(diagnostics[0].message, Catch::Contains("`test_scale` (conditioning) comes after `test_centroid`"));
}

TEST_CASE("a name that would put the run folder outside medax-runs/ is refused at the name", "[pipeline]") {
  const auto dir = scratch_dir("pipeline_name_escape");
  for (const std::string name : {"../..", "..", "a/b", "/tmp/x", "a\\\\b", "x..y", "\"a\\nb\""}) {
    INFO(name);
    check_single(dir, with_input("name: " + name + "\nstages:\n  - plugin: test_centroid\n"),
                 {2, 7, {"`name`", "must be one folder name", "any characters but '/', '\\'", "without '..'"}});
  }
  SECTION("the message names the problem") {
    const auto d = pipeline_errors(dir, with_input("name: ../..\nstages:\n  - plugin: test_centroid\n"));
    REQUIRE(d.size() == 1);
    CHECK_THAT(d[0].message, Catch::Contains("'../..' contains the path separator '/'"));
    CHECK_THAT(d[0].message, Catch::Contains("medax-runs/<name>-<input>"));
  }
  SECTION("ordinary names, spaces and dots included, are kept") {
    for (const std::string name : {"quickstart", "round trip", "v1.2-best_run", "résumé"}) {
      INFO(name);
      const auto file =
          medax::test::write_text(dir / "p.yaml", with_input("name: " + name + "\nstages:\n  - plugin: test_centroid\n"));
      CHECK(load_pipeline(file, medax::test::good_registry()).name == name);
    }
  }
  SECTION("without `name:`, a file whose stem is `..` is refused too") {
    const auto file = medax::test::write_text(dir / "...yaml", with_input("stages:\n  - plugin: test_centroid\n"));
    try {
      load_pipeline(file, medax::test::good_registry());
      FAIL("no error");
    } catch (const PipelineError& e) {
      REQUIRE(e.diagnostics().size() == 1);
      CHECK(e.diagnostics()[0].file == file.string());
      CHECK_THAT(e.diagnostics()[0].message, Catch::Contains("add `name: NAME`"));
    }
  }
}
