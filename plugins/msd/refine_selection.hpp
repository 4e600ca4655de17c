#pragma once
// Step 1a of the refinement (notes §2.8): the sub-surface of S a fitted primitive covers, by the
// authors' rules. A vertex is selected when its distance to T_P is below select_distance, or it
// is inside T_P, or the segment from its closest element point to it does not cross S and meets
// T_P within select_reach·ℓ̄ of it; an edge when both ends are, a triangle when all three edges are.
#include "primitive.hpp"
#include "refinement.hpp"
#include "target_mesh.hpp"

#include <vector>

namespace medax::msd::refine {

struct Selection {
  std::vector<Index> vertices;  ///< selected S vertices, ascending
  std::vector<Index> faces;     ///< selected S triangles, ascending
};

/// The selection of a fitted primitive; parallel over S's vertices, deterministic.
Selection select_subsurface(const Primitive& primitive, const TargetMesh& target, const RefineOptions& options);

}  // namespace medax::msd::refine
