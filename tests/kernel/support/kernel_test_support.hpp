#pragma once
// Helpers shared by the kernel tests: where the test plugin packages are built, a registry
// holding the good package, and small file helpers.
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>

#include <catch2/catch.hpp>
#include <test_paths.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace medax::test {

/// <build>/tests/plugins/<name>: one folder per plugin case (good, bad_abi, corrupt, ...).
inline std::filesystem::path plugin_dir(const std::string& name) {
  return std::filesystem::path(MEDAX_TEST_PLUGIN_ROOT) / name;
}

/// A registry with only the good test package loaded (shared; tests must not modify it).
inline const Registry& good_registry() {
  static Registry* registry = [] {
    auto* r = new Registry();
    r->load_directory(plugin_dir("good"));
    return r;
  }();
  return *registry;
}

/// The value a configured stage holds for parameter `name`, as `medax describe` writes it
/// (param_specs() reports the bound fields' current values).
inline std::string bound_value(Stage& stage, const std::string& name) {
  for (const ParamSpec& spec : stage.param_specs())
    if (spec.name == name) return spec.default_text();
  FAIL("the stage has no parameter " << name);
  return {};
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::filesystem::path write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// Absolute path of a bundled test mesh, for `input:` lines.
inline std::string data_file(const std::string& name) {
  return (std::filesystem::path(MEDAX_TEST_DATA_DIR) / name).string();
}

/// Loads `yaml` (written to `dir`/pipeline.yaml) and returns the diagnostics it raises; fails
/// the test when it loads without error.
inline std::vector<Diagnostic> pipeline_errors(const std::filesystem::path& dir, const std::string& yaml,
                                               const Overrides& overrides = {}) {
  const auto file = write_text(dir / "pipeline.yaml", yaml);
  try {
    load_pipeline(file, good_registry(), overrides);
  } catch (const PipelineError& e) {
    return e.diagnostics();
  }
  FAIL("the pipeline loaded without error");
  return {};
}

}  // namespace medax::test
