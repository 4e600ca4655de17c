#include "cgal_mesh.hpp"

namespace medax::services::detail {

std::size_t to_cgal(const SurfaceMesh& mesh, CgalMesh& out) {
  out.clear();
  out.reserve(mesh.vertices.size(), 3 * mesh.faces.size() / 2, mesh.faces.size());
  std::vector<CgalMesh::Vertex_index> vertices;
  vertices.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) vertices.push_back(out.add_vertex(to_point(v)));
  std::size_t skipped = 0;
  for (const Tri& f : mesh.faces)
    if (out.add_face(vertices[f[0]], vertices[f[1]], vertices[f[2]]) == CgalMesh::null_face()) ++skipped;
  return skipped;
}

}  // namespace medax::services::detail
