#include <medax/services/inside.hpp>

#include "cgal_mesh.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

namespace medax::services {

using detail::CgalMesh;
using detail::Kernel;

struct InsideTest::Impl {
  CgalMesh mesh;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<CgalMesh, Kernel>> side;
};

InsideTest::InsideTest(const SurfaceMesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (detail::to_cgal(mesh, impl_->mesh) != 0)
    throw std::invalid_argument("inside test: the mesh is not manifold (some faces could not be joined); "
                                "run the `repair` stage first");
  impl_->side = std::make_unique<CGAL::Side_of_triangle_mesh<CgalMesh, Kernel>>(impl_->mesh);
  (*impl_->side)(Kernel::Point_3(0, 0, 0));  // builds the AABB tree now, so later queries are read-only
}
InsideTest::~InsideTest() = default;
InsideTest::InsideTest(InsideTest&&) noexcept = default;
InsideTest& InsideTest::operator=(InsideTest&&) noexcept = default;

bool InsideTest::inside(const Vec3& p) const {
  return (*impl_->side)(detail::to_point(p)) == CGAL::ON_BOUNDED_SIDE;
}

std::vector<char> InsideTest::inside(const std::vector<Vec3>& points) const {
  std::vector<char> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { out[i] = inside(points[i]); });
  return out;
}

double winding_number(const SurfaceMesh& mesh, const Vec3& p) {
  // Sum of signed solid angles (Van Oosterom & Strackee 1983) over 4π.
  double total = 0;
  for (const Tri& f : mesh.faces) {
    const Vec3 a = mesh.vertices[f[0]] - p, b = mesh.vertices[f[1]] - p, c = mesh.vertices[f[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

}  // namespace medax::services
