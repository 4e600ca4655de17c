// Every stage's docs page holds its parameter table as the declarations make it today
// (`medax describe NAME --markdown`), so a documented default is the default that runs.
// Fix a failure with scripts/update-docs-params.sh.
#include "kernel_test_support.hpp"

#include <medax/kernel/param_table.hpp>

#include <catch2/catch.hpp>

using namespace medax;

TEST_CASE("every built-in stage's docs page holds its current parameter block", "[docs][params]") {
  Registry registry;
  registry.load_directory(medax::test::binary_dir() / MEDAX_PLUGIN_SUBDIR);
  CHECK(registry.errors().empty());
  REQUIRE(registry.stages().size() >= 20);
  for (const RegisteredStage* stage : registry.stages()) {
    const StageInfo& info = stage->info();
    INFO("stage " << info.name << ", page " << info.doc);
    REQUIRE_FALSE(info.doc.empty());
    const auto page = medax::test::source_dir() / info.doc.substr(0, info.doc.find('#'));  // no anchor
    REQUIRE(std::filesystem::exists(page));
    const std::string text = medax::test::read_text(page);
    const std::string block = param_block_markdown(info);
    INFO("expected block (run scripts/update-docs-params.sh):\n" << block);
    CHECK(text.find(block) != std::string::npos);
  }
}

TEST_CASE("every parameter has a doc string and a choice default among its choices", "[docs][params]") {
  Registry registry;
  registry.load_directory(medax::test::binary_dir() / MEDAX_PLUGIN_SUBDIR);
  for (const RegisteredStage* stage : registry.stages())
    for (const ParamSpec& p : stage->info().params) {
      INFO(stage->info().name << "." << p.name);
      CHECK_FALSE(p.doc.empty());
      if (p.type == ParamType::Choice)
        CHECK(std::find(p.choices.begin(), p.choices.end(), p.default_text()) != p.choices.end());
    }
}
