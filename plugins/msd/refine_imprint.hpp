#pragma once
// Steps 1b–2 of the refinement (notes §2.8): the patch is imprinted on T_P by direction-field
// projection and the template triangles under it are removed. A template vertex lies under the
// patch when the ray from its base along its direction meets the patch (exact ray–triangle test)
// or when it is within `margin` of the patch (clean-up: it would only make slivers); the ray from
// each patch vertex's base through it locates that vertex on T_P, and the triangle it meets goes
// too. Every template triangle with a vertex under the patch is removed.
#include "refine_patch.hpp"

#include <vector>

namespace medax::msd::refine {

/// Per template face: 1 when it is removed. `template_faces` index points [0, template_size).
std::vector<char> faces_under_patch(const std::vector<Tri>& template_faces, std::size_t template_size,
                                    const PointSet& points, const Patch& patch, double margin);

}  // namespace medax::msd::refine
