#pragma once
// The run folder contract (docs/pipeline-format.md, "What a run folder guarantees"): a run
// writes into a staging folder beside its target and is published whole when it ends, replacing
// a previous run folder in one step; stale staging folders of killed runs are removed.
#include <filesystem>
#include <string>
#include <vector>

namespace medax::detail {

struct RunFolder {
  std::filesystem::path target;   ///< where the run is published (as given with --out)
  std::filesystem::path staging;  ///< <target>.partial-<pid>
  bool linked = false;               ///< target is a symbolic link to staging while the run goes
  std::vector<std::string> removed;  ///< stale staging folders of killed runs, removed
};

/// Checks the target, removes stale staging folders of killed runs into it, creates the staging
/// folder; throws a message that says which path, why, and what to do.
RunFolder create_run_folder(const std::filesystem::path& dir);
/// Removes a staging folder that will not be published (and the link to it).
void discard(const RunFolder& folder);
/// Renames the staging folder into place; a previous run folder there is replaced in one step.
/// Throws, leaving the staging folder, when the target may not be replaced.
void publish(const RunFolder& folder);

}  // namespace medax::detail
