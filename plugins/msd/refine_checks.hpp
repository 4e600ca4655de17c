#pragma once
// Final checks of a refined primitive before it replaces T_P: no two triangles intersect (exact
// predicates), and the mesh wraps the element once (its image on the template surface ∂P^ρ0
// encloses the template's volume once, not twice).
#include <medax/geometry.hpp>

#include <vector>

namespace medax::msd::refine {

/// Exact self-intersection test of a closed 2-manifold triangle mesh (CGAL).
bool self_intersects(const std::vector<Vec3>& points, const std::vector<Tri>& faces);

/// Signed volume enclosed by a closed oriented triangle mesh.
double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Tri>& faces);

}  // namespace medax::msd::refine
