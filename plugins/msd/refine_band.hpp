#pragma once
// Step 4 of the refinement: the remaining template and the patch are joined. Every patch border
// is paired with the nearest border of the remaining template on ∂P^ρ0 and the band between
// them is triangulated (refine_stitch); a border that no band joins is capped (ear clipping on
// ∂P^ρ0). Remaining components no band joins lie inside the patch's directions (islands, or a
// remnant beyond a cap) and are dropped.
#include "refine_geometry.hpp"

#include <string>
#include <vector>

namespace medax::msd::refine {

struct Closure {
  std::vector<Tri> remaining;  ///< the template faces kept
  std::vector<Tri> band;
  std::string failure;         ///< empty on success
  std::vector<Index> failed_loop;  ///< the vertices of the patch borders no band or cap could close
};

/// Joins `patch` (non-empty, with at least one border) to `remaining`.
Closure close_band(const std::vector<Tri>& remaining, const std::vector<Tri>& patch,
                   const std::vector<FramedPoint>& points);

}  // namespace medax::msd::refine
