#pragma once
// Step 3 of the refinement (notes §2.8), on the template side: the patch vertices are S's own
// vertices already (their coordinates are copied, so they coincide with S exactly); the border
// ring of the remaining template is moved along its directions onto S (radius ρmax) where S is
// within `reach` of it, so that the band joins two rings lying on S instead of climbing from the
// fitted T_P up to S, which would tilt its triangles toward the element.
#include "refine_patch.hpp"

#include <vector>

namespace medax::msd::refine {

/// Snaps the border vertices of `remaining` (template ids) onto S; returns which were moved
/// (per template vertex).
std::vector<char> snap_template_border(const Primitive& primitive, const std::vector<Tri>& remaining, double reach,
                                       PointSet& points);

}  // namespace medax::msd::refine
