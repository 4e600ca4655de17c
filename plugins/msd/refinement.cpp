#include "refinement.hpp"

#include "refine_band.hpp"
#include "refine_checks.hpp"
#include "refine_imprint.hpp"
#include "refine_patch.hpp"
#include "refine_selection.hpp"
#include "refine_snap.hpp"
#include "refine_topology.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

namespace medax::msd {
namespace {

using refine::FramedPoint;
using refine::PointSet;

RefinedPrimitive unrefined(const Primitive& primitive, std::string note) {
  RefinedPrimitive result;
  if (primitive.fitted) {
    result.mesh = primitive_mesh(primitive);
    result.base = primitive.shape.base;
    result.input_vertex.assign(result.base.size(), kNotInput);
  }
  result.note = std::move(note);
  return result;
}

/// The template faces that survive the imprint, with the faces around border pinches removed
/// too until the border is a set of simple loops.
std::vector<Tri> remaining_faces(const std::vector<Tri>& faces, const std::vector<char>& removed) {
  std::vector<Tri> remaining;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (!removed[f]) remaining.push_back(faces[f]);
  while (true) {
    const refine::Borders borders = refine::border_loops(remaining);
    if (borders.pinches.empty()) return remaining;
    remaining.erase(std::remove_if(remaining.begin(), remaining.end(),
                                   [&](const Tri& t) {
                                     return std::any_of(t.begin(), t.end(), [&](Index v) {
                                       return std::binary_search(borders.pinches.begin(), borders.pinches.end(), v);
                                     });
                                   }),
                    remaining.end());
  }
}

/// The faces as a compact mesh (vertices in order of their point ids).
void assemble(const PointSet& points, const std::vector<Tri>& faces, RefinedPrimitive& result) {
  std::map<Index, Index> compact;
  for (const Tri& f : faces)
    for (Index v : f) compact.emplace(v, 0);
  for (auto& [point, id] : compact) {
    id = static_cast<Index>(result.mesh.vertices.size());
    result.mesh.vertices.push_back(points.points[point].position);
    result.base.push_back(points.points[point].base);
    result.input_vertex.push_back(points.input_vertex[point]);
  }
  for (const Tri& f : faces) result.mesh.faces.push_back({compact.at(f[0]), compact.at(f[1]), compact.at(f[2])});
}

/// Why the joined mesh cannot replace T_P, or empty: closed 2-manifold of genus 0, every new
/// triangle consistent, no self-intersection, and its image on ∂P^ρ0 wraps the element once.
std::string defect(const Primitive& primitive, const PointSet& points, const std::vector<Tri>& faces,
                   std::size_t new_from) {
  if (!refine::closed_manifold(faces)) return "the joined mesh is not a closed 2-manifold";
  std::map<Index, int> used;
  for (const Tri& f : faces)
    for (Index v : f) used.emplace(v, 0);
  if (static_cast<long>(used.size()) - static_cast<long>(faces.size() / 2) != 2)
    return "the joined mesh is not a topological sphere";
  for (std::size_t f = new_from; f < faces.size(); ++f)
    if (!refine::consistent_triangle(points.points[faces[f][0]], points.points[faces[f][1]], points.points[faces[f][2]]))
      return "a band or snapped triangle folds over along the direction field";
  std::vector<Vec3> position, image;
  for (const FramedPoint& p : points.points) {
    position.push_back(p.position);
    image.push_back(p.projected);
  }
  const double wraps = refine::enclosed_volume(image, faces) /
                       refine::enclosed_volume(primitive_vertices(primitive.shape, std::vector<double>(
                                                   primitive.shape.size(), primitive.initial_radius)),
                                               primitive.shape.faces);
  if (std::abs(wraps - 1) > 0.25) return fmt::format("the joined mesh wraps the element {:.2f} times", wraps);
  if (refine::self_intersects(position, faces)) return "the joined mesh intersects itself";
  return {};
}

/// Joins one patch to the template (steps 1b–4) on a copy of the points (the snap moves some);
/// the reason on failure, else empty with the mesh in `result`.
std::string join(const Primitive& primitive, const TargetMesh& target, const RefineOptions& options,
                 PointSet points, const refine::Patch& patch, RefinedPrimitive& result,
                 std::vector<Index>& failed_loop) {
  if (patch.faces.empty()) return "no selected S triangle faces away from the element";
  std::vector<Tri> faces;
  std::size_t new_from = 0;
  if (refine::border_loops(patch.faces).loops.empty()) {
    faces = patch.faces;  // S entirely covered by this primitive: the result is the patch itself
  } else {
    const std::vector<char> removed = refine::faces_under_patch(
        primitive.shape.faces, primitive.shape.size(), points, patch, options.cleanup_length * target.scale());
    const std::vector<Tri> remaining = remaining_faces(primitive.shape.faces, removed);
    const std::vector<char> snapped = refine::snap_template_border(
        primitive, remaining, options.select_reach * target.mean_edge_length(), points);
    const refine::Closure closure = refine::close_band(remaining, patch.faces, points.points);
    failed_loop = closure.failed_loop;
    if (!closure.failure.empty()) return closure.failure;
    // The template faces at a snapped vertex changed: they are checked like the new ones.
    const auto at_snapped = [&](const Tri& t) { return snapped[t[0]] || snapped[t[1]] || snapped[t[2]]; };
    for (const Tri& t : closure.remaining)
      if (!at_snapped(t)) faces.push_back(t);
    new_from = faces.size();
    for (const Tri& t : closure.remaining)
      if (at_snapped(t)) faces.push_back(t);
    faces.insert(faces.end(), patch.faces.begin(), patch.faces.end());
    faces.insert(faces.end(), closure.band.begin(), closure.band.end());
  }
  if (std::string why = defect(primitive, points, faces, new_from); !why.empty()) return why;
  assemble(points, faces, result);
  result.input_faces = patch.input_face;
  std::sort(result.input_faces.begin(), result.input_faces.end());
  result.refined = true;
  return {};
}

RefinedPrimitive refine_fitted(const Primitive& primitive, const TargetMesh& target, const RefineOptions& options) {
  const refine::Selection selection = refine::select_subsurface(primitive, target, options);
  PointSet points = refine::template_points(primitive);
  refine::Patch patch = refine::build_patch(primitive, target, selection.faces, options.hole_triangles, points);
  RefinedPrimitive result;
  std::vector<Index> failed_loop;
  std::string why = join(primitive, target, options, points, patch, result, failed_loop);
  // A patch whose band cannot be closed is retried without the ring along the borders that
  // failed (or its whole border ring), a few times.
  for (int shrink = 1; shrink <= options.shrink_retries && !why.empty() && !patch.faces.empty(); ++shrink) {
    patch = failed_loop.empty() ? refine::shrink_patch(patch) : refine::shrink_patch_at(patch, failed_loop);
    why = join(primitive, target, options, points, patch, result, failed_loop);
  }
  if (!why.empty()) result = unrefined(primitive, "not refined: " + why);
  result.selected_vertices = selection.vertices;
  result.selected_faces = selection.faces;
  return result;
}

}  // namespace

RefinedPrimitive refine_primitive(const Primitive& primitive, const TargetMesh& target, const RefineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RefinedPrimitive result = primitive.fitted ? refine_fitted(primitive, target, options)
                                             : unrefined(primitive, "not refined: the primitive is not fitted");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<RefinedPrimitive> refine_primitives(const std::vector<Primitive>& primitives, const TargetMesh& target,
                                                const RefineOptions& options) {
  std::vector<RefinedPrimitive> result(primitives.size());
  tbb::parallel_for(std::size_t{0}, primitives.size(),
                    [&](std::size_t k) { result[k] = refine_primitive(primitives[k], target, options); });
  return result;
}

}  // namespace medax::msd
