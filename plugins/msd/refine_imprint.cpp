#include "refine_imprint.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <iterator>

namespace medax::msd::refine {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>>>;

K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

Triangles triangles(const std::vector<Tri>& faces, const PointSet& points) {
  Triangles list;
  list.reserve(faces.size());
  for (const Tri& f : faces)
    list.emplace_back(point(points.points[f[0]].position), point(points.points[f[1]].position),
                      point(points.points[f[2]].position));
  return list;
}

K::Ray_3 ray(const FramedPoint& p, const Vec3& through) { return {point(p.base), point(through)}; }

/// Template vertices whose ray meets the patch or that are within `margin` of it.
std::vector<char> vertices_under(std::size_t template_size, const PointSet& points, const Tree& patch, double margin) {
  std::vector<char> under(template_size, 0);
  for (std::size_t i = 0; i < template_size; ++i) {
    const FramedPoint& p = points.points[i];
    under[i] = patch.do_intersect(ray(p, p.projected)) || patch.squared_distance(point(p.position)) < margin * margin;
  }
  return under;
}

}  // namespace

std::vector<char> faces_under_patch(const std::vector<Tri>& template_faces, std::size_t template_size,
                                    const PointSet& points, const Patch& patch, double margin) {
  const Triangles patch_triangles = triangles(patch.faces, points);
  Tree patch_tree(patch_triangles.cbegin(), patch_triangles.cend());
  patch_tree.accelerate_distance_queries();
  const std::vector<char> under = vertices_under(template_size, points, patch_tree, margin);
  std::vector<char> removed(template_faces.size(), 0);
  for (std::size_t f = 0; f < template_faces.size(); ++f)
    for (Index v : template_faces[f]) removed[f] = removed[f] || under[v];
  // The triangles the patch vertices' rays meet.
  const Triangles template_triangles = triangles(template_faces, points);
  Tree template_tree(template_triangles.cbegin(), template_triangles.cend());
  std::vector<char> in_patch(points.points.size(), 0);
  for (const Tri& f : patch.faces)
    for (Index v : f) in_patch[v] = 1;
  std::vector<Tree::Primitive_id> hits;
  for (std::size_t v = 0; v < in_patch.size(); ++v)
    if (in_patch[v])
      template_tree.all_intersected_primitives(ray(points.points[v], points.points[v].position), std::back_inserter(hits));
  for (const Tree::Primitive_id& hit : hits) removed[static_cast<std::size_t>(hit - template_triangles.cbegin())] = 1;
  return removed;
}

}  // namespace medax::msd::refine
