#include "refine_selection.hpp"

#include "coverage.hpp"
#include "refine_geometry.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace medax::msd::refine {
namespace {

/// The segment from b = cp(x; P) to x stays inside S: the first place where the ray from b
/// leaves S is x itself (b is inside S because the element is).
bool reaches_without_crossing(const TargetMesh& target, const Vec3& base, const Vec3& x) {
  const double length = (x - base).norm();
  if (!(length > 0)) return true;
  // No exit found at all happens when the ray passes exactly through a vertex or edge of S
  // (x itself is a vertex): nothing crosses before x then either.
  const auto exit = target.first_exit(base, (x - base) / length);
  return !exit || *exit >= length * (1 - 1e-9);
}

bool selected_vertex(const PrimitiveShape& shape, const Primitive& primitive, const TargetMesh& target,
                     const Vec3& x, double distance, double reach) {
  if (std::abs(shape.signed_distance(x)) < distance) return true;
  const double radial = shape.radial(x);  // ℰ(x; T_P): negative inside, else the gap along the ray
  if (radial <= 0) return true;
  return radial < reach && reaches_without_crossing(target, primitive.element.closest_point(x), x);
}

}  // namespace

Selection select_subsurface(const Primitive& primitive, const TargetMesh& target, const RefineOptions& options) {
  Selection selection;
  if (!primitive.fitted) return selection;
  const PrimitiveShape shape(primitive);
  const double distance = options.select_distance * target.scale();
  const double reach = options.select_reach * target.mean_edge_length();
  const SurfaceMesh& s = target.mesh();
  std::vector<char> chosen(s.vertices.size(), 0);
  tbb::parallel_for(std::size_t{0}, s.vertices.size(), [&](std::size_t v) {
    if (shape.near(s.vertices[v], std::max(distance, reach)))
      chosen[v] = selected_vertex(shape, primitive, target, s.vertices[v], distance, reach);
  });
  for (std::size_t v = 0; v < chosen.size(); ++v)
    if (chosen[v]) selection.vertices.push_back(static_cast<Index>(v));
  // A triangle's three edges are selected exactly when its three vertices are.
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    if (chosen[s.faces[f][0]] && chosen[s.faces[f][1]] && chosen[s.faces[f][2]])
      selection.faces.push_back(static_cast<Index>(f));
  return selection;
}

}  // namespace medax::msd::refine
