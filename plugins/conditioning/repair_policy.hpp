#pragma once
// The `repair` stage's policy: run the repair service, then accept the result or compose the
// refusal that names every problem with its fix.
#include <medax/services/mesh_check.hpp>

#include <string>
#include <vector>

namespace medax::conditioning {

struct RepairDecision {
  bool accept = false;
  /// When refused: the whole error text (first line a summary, then one line per problem).
  std::string refusal;
  /// When accepted: problems left that do not stop the pipeline (one line each), for warnings.
  std::vector<std::string> warnings;
};

/// `source` names the mesh in the message (a path; only its file name is shown).
RepairDecision decide_repair(const services::RepairResult& result, const services::RepairOptions& options,
                             const std::string& source);

}  // namespace medax::conditioning
