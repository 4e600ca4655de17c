#pragma once
// Finds plugin libraries, checks their stamp, and keeps the stages they register.
#include <medax/plugin.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace medax {

struct PackageInfo {
  std::string name;
  std::string version;
  std::filesystem::path file;
};

struct RegisteredStage {
  StageEntry entry;
  std::shared_ptr<const PackageInfo> package;
  const StageInfo& info() const { return entry.info; }
};

class Registry {
 public:
  Registry();
  ~Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  /// Plugin folders in search order: the folder beside the running kernel library
  /// (lib/medax/plugins in the build tree or the install prefix), then each entry of
  /// MEDAX_PLUGIN_PATH (':'-separated).
  static std::vector<std::filesystem::path> search_path();

  /// Loads every plugin library in the search path. Problems become errors(), never throws.
  void load_default();
  /// Loads every `*.so` in `dir` (sorted by name). A package already loaded from an earlier
  /// folder shadows a later file of the same name.
  void load_directory(const std::filesystem::path& dir);
  /// Loads one plugin library; returns false and records one error line on failure.
  bool load_file(const std::filesystem::path& file);
  /// Registers stages directly (tests, statically linked stages).
  void add_package(const PackageInfo& package, const PluginRegistrar& registrar);

  /// One line per plugin that could not be loaded or registered.
  const std::vector<std::string>& errors() const { return errors_; }
  /// The error lines of the plugin files that failed to load and may have provided `stage`: by
  /// the medax_add_plugin naming, libmedax_PKG.so provides PKG and PKG_* (a file that did not
  /// load cannot say what it holds).
  std::vector<std::string> failures_for(std::string_view stage) const;
  const RegisteredStage* find(std::string_view name) const;
  /// Up to three registered names closest to `name` (edit distance), best first.
  std::vector<std::string> suggest(std::string_view name) const;
  /// All stages, ordered by role then name.
  std::vector<const RegisteredStage*> stages() const;
  std::unique_ptr<Stage> create(std::string_view name) const;

  /// The process-wide registry, loaded from the default search path on first use.
  static Registry& global();

 private:
  struct Libraries;
  std::unique_ptr<Libraries> libraries_;
  std::vector<RegisteredStage> stages_;
  std::vector<std::string> errors_;
  /// The files that failed to load, each with its line in errors_.
  std::vector<std::pair<std::filesystem::path, std::string>> failed_files_;
  void fail(const std::filesystem::path& file, std::string line);
};

}  // namespace medax
