// Plugin registry: loading, listing order, one clear error line per broken plugin, shadowing
// and name suggestions.
#include "kernel_test_support.hpp"

#include <medax/kernel/registry.hpp>

#include <cstdlib>

using namespace medax;
using medax::test::plugin_dir;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Loads one case folder into a fresh registry and returns its single error line.
std::string single_error(const std::string& case_name) {
  Registry registry;
  registry.load_directory(plugin_dir(case_name));
  REQUIRE(registry.errors().size() == 1);
  CHECK(registry.stages().empty());
  return registry.errors().front();
}

}  // namespace

TEST_CASE("registry loads every stage of the good package with its package info", "[registry]") {
  Registry registry;
  registry.load_directory(plugin_dir("good"));
  REQUIRE(registry.errors().empty());
  REQUIRE(registry.stages().size() == 9);

  const RegisteredStage* scale = registry.find("test_scale");
  REQUIRE(scale);
  CHECK(scale->info().role == Role::Conditioning);
  CHECK(scale->package->name == "kernel_test");
  CHECK(scale->package->version == "1.2.3");
  CHECK(scale->package->file == plugin_dir("good") / "libmedax_kernel_test_good.so");
  REQUIRE(scale->info().params.size() == 1);
  CHECK(scale->info().params[0].name == "factor");
  CHECK(registry.find("test_centroid")->info().role == Role::Extraction);
  CHECK(registry.find("test_count")->info().role == Role::Evaluation);
  CHECK(registry.find("no_such_stage") == nullptr);

  auto stage = registry.create("test_centroid");
  REQUIRE(stage);
  CHECK(dynamic_cast<ExtractionStage*>(stage.get()) != nullptr);
  CHECK_THROWS_AS(registry.create("no_such_stage"), std::invalid_argument);
}

TEST_CASE("registry lists stages ordered by role then name", "[registry]") {
  Registry registry;
  registry.load_directory(plugin_dir("good"));
  std::vector<std::string> names;
  for (const RegisteredStage* s : registry.stages()) names.push_back(s->info().name);
  CHECK(names == std::vector<std::string>{"test_scale",                                   // conditioning
                                          "test_centroid", "test_oracle_centroid",        // extraction
                                          "test_publish", "test_radius_field",            // significance
                                          "test_fail",                                    // simplification
                                          "test_consume", "test_count", "test_random"});  // evaluation
}

TEST_CASE("a plugin with a wrong ABI stamp gives one error line and registers nothing", "[registry]") {
  const std::string error = single_error("bad_abi");
  CHECK(contains(error, (plugin_dir("bad_abi") / "libmedax_kernel_test_bad_abi.so").string()));
  CHECK(contains(error, "ABI " + std::to_string(kAbiVersion + 1000)));
  CHECK(contains(error, "rebuild"));
}

TEST_CASE("a corrupt .so gives one error line", "[registry]") {
  const std::string error = single_error("corrupt");
  CHECK(contains(error, (plugin_dir("corrupt") / "libmedax_kernel_test_corrupt.so").string()));
  CHECK(contains(error, "cannot be loaded"));
  CHECK(contains(error, "file too short"));  // the loader's own words, not an errno text
}

TEST_CASE("a library without medax_plugin_entry gives one error line", "[registry]") {
  const std::string error = single_error("no_entry");
  CHECK(contains(error, (plugin_dir("no_entry") / "libmedax_kernel_test_no_entry.so").string()));
  CHECK(contains(error, "medax_plugin_entry"));
}

TEST_CASE("a missing plugin file gives one error line and a missing folder is skipped", "[registry]") {
  Registry registry;
  const auto missing = plugin_dir("good") / "libmedax_does_not_exist.so";
  CHECK_FALSE(registry.load_file(missing));
  REQUIRE(registry.errors().size() == 1);
  CHECK(contains(registry.errors()[0], missing.string()));
  registry.load_directory(plugin_dir("no_such_case_folder"));
  CHECK(registry.errors().size() == 1);
}

TEST_CASE("a duplicate stage name is reported once and the first registration wins", "[registry]") {
  Registry registry;
  registry.load_directory(plugin_dir("good"));
  registry.load_directory(plugin_dir("duplicate"));
  REQUIRE(registry.errors().size() == 1);
  const std::string& error = registry.errors()[0];
  CHECK(contains(error, (plugin_dir("duplicate") / "libmedax_kernel_test_duplicate.so").string()));
  CHECK(contains(error, "'test_centroid'"));
  CHECK(contains(error, "already registered"));
  CHECK(registry.find("test_centroid")->package->name == "kernel_test");
  // The duplicate package's other stage is still available.
  REQUIRE(registry.find("test_duplicate_own"));
  CHECK(registry.find("test_duplicate_own")->package->name == "kernel_test_duplicate");
}

TEST_CASE("loading every broken case together gives one error per broken file", "[registry]") {
  Registry registry;
  for (const char* dir : {"good", "bad_abi", "corrupt", "no_entry", "duplicate"})
    registry.load_directory(plugin_dir(dir));
  CHECK(registry.errors().size() == 4);
  CHECK(registry.stages().size() == 10);  // 9 good + the duplicate package's own stage
}

TEST_CASE("a plugin file in an earlier folder shadows a file of the same name in a later one", "[registry]") {
  // tests/plugins/shadow holds a copy of the good package under the same file name.
  SECTION("good first: the copy is skipped without a duplicate error") {
    Registry registry;
    registry.load_directory(plugin_dir("good"));
    registry.load_directory(plugin_dir("shadow"));
    CHECK(registry.errors().empty());
    CHECK(registry.stages().size() == 9);
    CHECK(registry.find("test_scale")->package->file.parent_path() == plugin_dir("good"));
  }
  SECTION("shadow first: the copy is the one used") {
    Registry registry;
    registry.load_directory(plugin_dir("shadow"));
    registry.load_directory(plugin_dir("good"));
    CHECK(registry.errors().empty());
    CHECK(registry.find("test_scale")->package->file.parent_path() == plugin_dir("shadow"));
  }
}

TEST_CASE("search path is the kernel plugin folder then MEDAX_PLUGIN_PATH entries", "[registry]") {
  ::setenv("MEDAX_PLUGIN_PATH", "/tmp/medax-a::/tmp/medax-b", 1);
  const auto dirs = Registry::search_path();
  ::unsetenv("MEDAX_PLUGIN_PATH");
  REQUIRE(dirs.size() == 3);
  CHECK(dirs[0] == std::filesystem::path(MEDAX_BINARY_DIR) / "lib" / "medax" / "plugins");
  CHECK(dirs[1] == "/tmp/medax-a");
  CHECK(dirs[2] == "/tmp/medax-b");
}

TEST_CASE("suggest() offers the closest registered names best first", "[registry]") {
  const Registry& registry = medax::test::good_registry();
  const auto typo = registry.suggest("test_centriod");
  REQUIRE_FALSE(typo.empty());
  CHECK(typo.front() == "test_centroid");
  CHECK(typo.size() <= 3);
  const auto prefix = registry.suggest("oracle");
  REQUIRE_FALSE(prefix.empty());
  CHECK(prefix.front() == "test_oracle_centroid");
  CHECK(registry.suggest("completely_unrelated_words").empty());
}
