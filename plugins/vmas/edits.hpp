#pragma once
// Scripted edits (the paper's interactive split/remove, replayed from a pipeline): one edit per
// line or per ';'
//
//     split  X Y Z [after K|end]    split the sphere whose centre is nearest to (X, Y, Z)
//     remove X Y Z [after K|end]    remove the sphere nearest to (X, Y, Z)
//     add    X Y Z [after K|end]    add the shrinking ball of the surface vertex nearest to (X, Y, Z)
//
// `after K` applies the edit once K iterations have completed (K ≥ 0; 0 = before the first
// iteration); `after end` (the default) once the optimisation has stopped. Coordinates may be
// separated by spaces or commas and wrapped in [ ] or ( ); a leading "- " and '#' comments are
// ignored, so a YAML block scalar can hold a list:
//
//     edits: |
//       - split [0.30, 0.10, 0.20] after 40
//       - remove [-0.20, 0.00, 0.10]
#include "vmas.hpp"

#include <string>
#include <vector>

namespace medax::vmas {

enum class EditOp { Split, Remove, Add };

struct Edit {
  static constexpr int kEnd = -1;
  EditOp op = EditOp::Split;
  Vec3 point = Vec3::Zero();
  int after = kEnd;  ///< iterations completed before it applies; kEnd = after the run
  std::string text;  ///< the edit as written (for logs)
};

/// Parses a script; throws std::invalid_argument naming the bad edit and what is expected.
/// The result is ordered by `after` (end last), keeping the script's order among equals.
std::vector<Edit> parse_edits(const std::string& script);

/// Applies one edit (point in the solver's input frame). Returns a line for the log.
std::string apply_edit(VmasSolver& solver, const Edit& edit, const Vec3& point);

}  // namespace medax::vmas
