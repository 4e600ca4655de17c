#pragma once
// One stage of a built plugin package, loaded as the kernel loads it, and configured instances
// of it for direct calls.
#include <medax/kernel/registry.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace medax::test {

template <typename RoleStage>
struct LoadedStage {
  Registry registry;
  const RegisteredStage* stage = nullptr;
  std::string name;

  LoadedStage(const std::filesystem::path& plugin, std::string stage_name) : name(std::move(stage_name)) {
    REQUIRE(registry.load_file(plugin));
    stage = registry.find(name);
    REQUIRE(stage);
  }
  /// An instance at its declared defaults, with `changes` applied.
  std::unique_ptr<RoleStage> create(const std::map<std::string, ParamValue>& changes = {}) const {
    std::unique_ptr<Stage> s = registry.create(name);
    auto* typed = dynamic_cast<RoleStage*>(s.get());
    REQUIRE(typed);
    ParamSet params;
    for (const auto& [key, value] : changes) params.set(key, value);
    s->configure(params);
    s.release();
    return std::unique_ptr<RoleStage>(typed);
  }
};

}  // namespace medax::test
