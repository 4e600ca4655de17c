#pragma once
// The one collector of pipeline and sweep file problems: every problem found in one pass, each
// as file:line:column with what to do, thrown together as a PipelineError.
#include <medax/kernel/pipeline.hpp>

#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

namespace medax::detail {

/// Collects diagnostics against one file; nodes from --set carry their own origin.
class Diagnostics {
 public:
  explicit Diagnostics(std::string file) : file_(std::move(file)) {}

  /// A problem at `at` (its line and column when it has a position in the file).
  void error(const YAML::Node& at, std::string message);
  /// A problem with no position, under `where` (e.g. "--set a.b=1").
  void error_at(const std::string& where, std::string message);
  /// Marks a node that came from `where` rather than from the file.
  void mark_overridden(const YAML::Node& node, std::string where) { overridden_.emplace_back(node, std::move(where)); }
  /// Reports every key of `map` not in `known`, with a "did you mean".
  void unknown_keys(const YAML::Node& map, const std::vector<std::string>& known, const char* what);
  /// Reports every key that appears twice in one map, anywhere under `root`, at its second
  /// occurrence (yaml-cpp keeps both entries but lookups see only the first). Call it on the
  /// document as read, before any node is added or changed.
  void duplicate_keys(const YAML::Node& root);

  bool ok() const { return diagnostics_.empty(); }
  std::vector<Diagnostic> take() { return std::move(diagnostics_); }
  void throw_if_any();
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<std::pair<YAML::Node, std::string>> overridden_;
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace medax::detail
