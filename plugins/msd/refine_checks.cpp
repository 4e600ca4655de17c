#include "refine_checks.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

namespace medax::msd::refine {

bool self_intersects(const std::vector<Vec3>& points, const std::vector<Tri>& faces) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<K::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(points.size());
  for (const Vec3& p : points) vertex.push_back(mesh.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for (const Tri& f : faces)
    if (mesh.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]) == Mesh::null_face()) return true;
  return CGAL::Polygon_mesh_processing::does_self_intersect<CGAL::Sequential_tag>(mesh);
}

double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Tri>& faces) {
  double volume = 0;
  for (const Tri& f : faces) volume += points[f[0]].dot(points[f[1]].cross(points[f[2]])) / 6;
  return volume;
}

}  // namespace medax::msd::refine
