#include "repair_policy.hpp"

#include <filesystem>

namespace medax::conditioning {

namespace {

using services::MeshProblem;
using services::MeshProblemKind;

/// Problems that stop a pipeline (a medial axis needs a closed, manifold, outward-oriented
/// surface without self-intersections); the others are tolerated once repair has run.
bool blocking(const MeshProblem& p) {
  switch (p.kind) {
    case MeshProblemKind::DuplicateVertices:
    case MeshProblemKind::DegenerateFaces:
    case MeshProblemKind::DuplicateFaces:
    case MeshProblemKind::UnreferencedVertices:
      return false;
    default:
      return true;
  }
}

/// The problem without its fix: "N self-intersecting triangle pairs (M faces)".
std::string what_only(const std::string& message) {
  const auto colon = message.find("): ");
  return colon == std::string::npos ? message : message.substr(0, colon + 1);
}

void add_lines(std::string& text, const std::vector<MeshProblem>& problems, bool want_blocking, bool with_fix = true) {
  for (const MeshProblem& p : problems)
    if (blocking(p) == want_blocking) text += "\n  - " + (with_fix ? p.message : what_only(p.message));
}

}  // namespace

RepairDecision decide_repair(const services::RepairResult& result, const services::RepairOptions& options,
                             const std::string& source) {
  RepairDecision decision;
  const auto after = result.after.problems();
  if (result.ok()) {
    decision.accept = true;
    // What is left, without the fix (which would be to run repair again).
    for (const MeshProblem& p : after) decision.warnings.push_back("left as is: " + what_only(p.message));
    if (!result.after.self_intersecting)
      decision.warnings.push_back("self-intersections were not tested (check_self_intersections: false)");
    return decision;
  }

  const std::string name = source.empty() ? "the mesh" : std::filesystem::path(source).filename().string();
  std::string& text = decision.refusal;
  text = "refusing " + name +
         ": the medial axis needs a closed, manifold, outward-oriented surface free of self-intersections.";
  const auto before = result.before.problems();
  bool input_blocking = false;
  for (const MeshProblem& p : before) input_blocking |= blocking(p) && !p.automatic;
  if (!before.empty()) {
    text += "\nThe input has:";
    add_lines(text, before, true);
    add_lines(text, before, false);
  }
  const bool asked = options.fill_holes || options.remove_self_intersections;
  if (asked || !input_blocking) {
    if (asked)
      text += "\nRepair was asked for (fill_holes: " + std::string(options.fill_holes ? "true" : "false") +
              ", remove_self_intersections: " + std::string(options.remove_self_intersections ? "true" : "false") +
              ") but did not give a valid mesh:";
    else
      text += "\nThe automatic repairs did not give a valid mesh:";
    for (const std::string& f : result.failures) text += "\n  - " + f;
    text += "\nWhat remains after repair:";
    add_lines(text, after, true, !asked);
    if (asked)
      text += "\nFix these in a mesh editor or a dedicated repair tool (e.g. MeshLab, Blender's 3D-Print "
              "Toolbox), then run again.";
  }
  return decision;
}

}  // namespace medax::conditioning
