#include <medax/services/closest_point.hpp>

#include "cgal_mesh.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <tbb/parallel_for.h>

namespace medax::services {

using detail::Kernel;
using Triangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct SurfaceDistance::Impl {
  Triangles triangles;
  Tree tree;
};

SurfaceDistance::SurfaceDistance(const SurfaceMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->triangles.reserve(mesh.faces.size());
  for (const Tri& f : mesh.faces)
    impl_->triangles.emplace_back(detail::to_point(mesh.vertices[f[0]]), detail::to_point(mesh.vertices[f[1]]),
                                  detail::to_point(mesh.vertices[f[2]]));
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}
SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

ClosestPoint SurfaceDistance::closest(const Vec3& p) const {
  const Kernel::Point_3 q = detail::to_point(p);
  const auto [point, primitive] = impl_->tree.closest_point_and_primitive(q);
  ClosestPoint out;
  out.point = detail::to_vec(point);
  out.face = static_cast<Index>(primitive - impl_->triangles.begin());
  out.distance = (out.point - p).norm();
  return out;
}

std::vector<double> SurfaceDistance::distances(const std::vector<Vec3>& points) const {
  std::vector<double> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { out[i] = distance(points[i]); });
  return out;
}

}  // namespace medax::services
