#pragma once
// The patch of a primitive: the selected S triangles it can take over exactly, numbered in the
// refinement's point list (template vertices first, then patch vertices). A selected triangle is
// kept when it faces away from its corners' bases (in space and on ∂P^ρ0); triangles around a
// vertex where the patch border touches itself are dropped until the border is a set of loops.
// Small holes (a vertex the selection missed) are filled with S's triangles there.
#include "primitive.hpp"
#include "refine_geometry.hpp"
#include "refinement.hpp"
#include "target_mesh.hpp"

#include <vector>

namespace medax::msd::refine {

/// Every point of the refinement: the template's vertices, then the patch's S vertices.
struct PointSet {
  std::vector<FramedPoint> points;
  std::vector<Index> input_vertex;  ///< the S vertex a point is, or kNoVertex
};
inline constexpr Index kNoVertex = kNotInput;

/// The fitted T_P's vertices: b_i + ρ_i d_i, base b_i, image b_i + ρ0 d_i.
PointSet template_points(const Primitive& primitive);

struct Patch {
  std::vector<Tri> faces;         ///< in PointSet ids
  std::vector<Index> input_face;  ///< the S triangle of each face
};

/// The patch of the selected S triangles `selected`, its holes of at most `hole_limit` S
/// triangles filled; adds its vertices to `points`.
Patch build_patch(const Primitive& primitive, const TargetMesh& target, const std::vector<Index>& selected,
                  std::size_t hole_limit, PointSet& points);

/// The patch without its border ring (the faces touching a border vertex): a retry when the
/// band cannot be closed, e.g. because the patch's hole is narrower than the template spacing.
Patch shrink_patch(const Patch& patch);
/// The patch without the faces touching `loop` (the vertices of borders that could not be joined).
Patch shrink_patch_at(const Patch& patch, std::vector<Index> loop);

}  // namespace medax::msd::refine
