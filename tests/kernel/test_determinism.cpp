// Same config and seed give the same bytes; each stage's RNG stream depends only on the seed
// and its id.
#include "run_helpers.hpp"

using namespace medax;
using medax::test::data_file;
using medax::test::read_json;
using medax::test::read_text;
using medax::test::run_yaml;
using medax::test::scratch_dir;

namespace {
const std::string kInput = "input: " + data_file("ellipsoid.off") + "\n";

/// metrics.json of a run of `stages` with `seed`.
nlohmann::json run_metrics(const std::string& name, const std::string& stages, int seed) {
  const auto run = run_yaml(scratch_dir(name), kInput + "seed: " + std::to_string(seed) + "\nstages:\n" + stages);
  REQUIRE(run.result.ok);
  return read_json(run.dir / "metrics.json");
}

const std::string kTwoRandomStages = "  - plugin: test_centroid\n"
                                     "  - {plugin: test_random, id: a}\n"
                                     "  - {plugin: test_random, id: b}\n";
}  // namespace

TEST_CASE("two runs of the same config and seed give byte-identical outputs", "[runner][determinism]") {
  const std::string yaml = kInput + "seed: 11\nstages:\n"
                                    "  - plugin: test_scale\n    params: {factor: 0.3}\n"
                                    "  - plugin: test_oracle_centroid\n"
                                    "  - plugin: test_random\n"
                                    "  - plugin: test_count\n"
                                    "outputs: {medial: [ma, ply]}\n";
  const auto first = run_yaml(scratch_dir("determinism_first"), yaml);
  const auto second = run_yaml(scratch_dir("determinism_second"), yaml);
  REQUIRE(first.result.ok);
  REQUIRE(second.result.ok);
  for (const char* file : {"medial.ma", "medial.ply", "metrics.json", "config.resolved.yaml"}) {
    INFO(file);
    const std::string a = read_text(first.dir / file);
    CHECK_FALSE(a.empty());
    CHECK(a == read_text(second.dir / file));
  }
}

TEST_CASE("stage RNG streams differ by stage id and are reproducible", "[runner][determinism]") {
  const auto first = run_metrics("rng_first", kTwoRandomStages, 5);
  const auto again = run_metrics("rng_again", kTwoRandomStages, 5);
  CHECK(first["a"]["first"] != first["b"]["first"]);
  CHECK(first["a"]["mean"] != first["b"]["mean"]);
  CHECK(first == again);

  // A stage's stream does not depend on what other stages draw before it.
  const auto alone = run_metrics("rng_alone", "  - plugin: test_centroid\n  - {plugin: test_random, id: b}\n", 5);
  CHECK(alone["b"] == first["b"]);

  // Another seed gives other streams.
  const auto reseeded = run_metrics("rng_reseeded", kTwoRandomStages, 6);
  CHECK(reseeded["a"]["first"] != first["a"]["first"]);
  CHECK(reseeded["b"]["first"] != first["b"]["first"]);
}
