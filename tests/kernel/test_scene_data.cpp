// Typed scene data: payloads that one stage publishes and a later one reads, with an error
// that names the stage to put first, and the run-folder file of a key with a writer.
#include "run_helpers.hpp"

#include <medax/context.hpp>
#include <medax/scene_data.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <ostream>
#include <sstream>

using namespace medax;

namespace {
struct Burn {
  std::vector<double> times;
};
const DataKey<Burn> kBurn{"test.burn", "test_burner"};
const DataKey<int> kCount{"test.count", "test_counter", "count.txt",
                          [](const int& n, std::ostream& out) { out << "count " << n << '\n'; }};
}  // namespace

TEST_CASE("a published payload is read back by its key, unchanged", "[scene_data]") {
  SceneData data;
  CHECK(data.find(kBurn) == nullptr);
  data.publish(kBurn, Burn{{1.0, 2.5}}, "burner");
  REQUIRE(data.find(kBurn) != nullptr);
  CHECK(data.get(kBurn).times == std::vector<double>{1.0, 2.5});
  CHECK(data.publisher("test.burn") == "burner");
  data.publish(kBurn, Burn{{7.0}}, "again");  // a later stage replaces it
  CHECK(data.get(kBurn).times == std::vector<double>{7.0});
  CHECK(data.publisher("test.burn") == "again");
}

TEST_CASE("a missing payload names the stage that makes it", "[scene_data]") {
  SceneData data;
  CHECK_THROWS_AS(data.get(kBurn), MissingData);
  CHECK_THROWS_WITH(data.get(kBurn), Catch::Contains("'test.burn'") && Catch::Contains("`test_burner` stage"));
}

TEST_CASE("a payload read as another type is a programming error, not a crash", "[scene_data]") {
  SceneData data;
  data.publish(kBurn, Burn{}, "burner");
  const DataKey<int> same_name{"test.burn", "x"};
  CHECK_THROWS_AS(data.find(same_name), std::logic_error);
}

TEST_CASE("copies of a scene share payloads and keep their own entries", "[scene_data]") {
  SceneData a;
  a.publish(kBurn, Burn{{1.0}}, "burner");
  SceneData b = a;
  CHECK(&a.get(kBurn) == &b.get(kBurn));  // shared, not copied
  b.erase("test.burn");
  CHECK(a.find(kBurn) != nullptr);
  CHECK(b.find(kBurn) == nullptr);
}

TEST_CASE("a key with a writer gives a run-folder file named after the publishing stage", "[scene_data]") {
  SceneData data;
  data.publish(kBurn, Burn{}, "burner");  // no writer: no file
  data.publish(kCount, 42, "counter");
  const auto outputs = data.outputs();
  REQUIRE(outputs.size() == 1);
  CHECK(outputs[0].file == "counter_count.txt");
  std::ostringstream text;
  outputs[0].write(text);
  CHECK(text.str() == "count 42\n");
}

TEST_CASE("a context publishes as its stage", "[scene_data]") {
  BasicContext ctx(0, false, "my_stage");
  ctx.publish(kCount, 3);
  CHECK(ctx.data().get(kCount) == 3);
  CHECK(ctx.data().publisher("test.count") == "my_stage");
}

TEST_CASE("in a run, a stage reads what an earlier one published and the payload's file is written",
          "[scene_data][runner]") {
  const std::string input = "input: " + medax::test::data_file("cube.off") + "\n";
  const auto run = medax::test::run_yaml(medax::test::scratch_dir("scene_data_run"),
                                         input + "stages:\n  - plugin: test_centroid\n"
                                                 "  - {plugin: test_publish, id: publisher}\n"
                                                 "  - plugin: test_consume\n");
  INFO(run.result.error);
  REQUIRE(run.result.ok);
  const auto metrics = medax::test::read_json(run.dir / "metrics.json");
  CHECK(metrics["test_consume"]["largest_radius"].get<double>() == Approx(std::sqrt(3.0)));
  CHECK(medax::test::read_text(run.dir / "publisher_largest_radius.txt").rfind("1.73205", 0) == 0);
}

TEST_CASE("in a run, reading what no stage published stops the run naming the stage to add",
          "[scene_data][runner]") {
  const std::string input = "input: " + medax::test::data_file("cube.off") + "\n";
  const auto run = medax::test::run_yaml(medax::test::scratch_dir("scene_data_missing"),
                                         input + "stages:\n  - plugin: test_centroid\n  - plugin: test_consume\n");
  CHECK_FALSE(run.result.ok);
  CHECK(run.result.failed_stage == "test_consume");
  CHECK_THAT(run.result.error, Catch::StartsWith("test_consume: needs 'test.largest_radius'") &&
                                   Catch::Contains("put a `test_publish` stage before this one"));
}
