#include "coverage.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace medax::msd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>>>;

K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
Vec3 vec(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }


}  // namespace

struct PrimitiveShape::Impl {
  SkeletonElement element;
  Triangles triangles;
  AabbTree tree;
  Eigen::AlignedBox3d box;
};

PrimitiveShape::PrimitiveShape(const Primitive& primitive) : impl_(std::make_unique<Impl>()) {
  impl_->element = primitive.element;
  const std::vector<Vec3> x = primitive_vertices(primitive.shape, primitive.radius);
  for (const Vec3& v : x) impl_->box.extend(v);
  impl_->triangles.reserve(primitive.shape.faces.size());
  for (const Tri& f : primitive.shape.faces) impl_->triangles.emplace_back(point(x[f[0]]), point(x[f[1]]), point(x[f[2]]));
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

PrimitiveShape::~PrimitiveShape() = default;
PrimitiveShape::PrimitiveShape(PrimitiveShape&&) noexcept = default;
PrimitiveShape& PrimitiveShape::operator=(PrimitiveShape&&) noexcept = default;

double PrimitiveShape::radial(const Vec3& x) const {
  const Vec3 p = impl_->element.closest_point(x);
  const double length = (x - p).norm();
  if (length == 0) return -std::numeric_limits<double>::infinity();  // on the element: inside
  const Vec3 d = (x - p) / length;
  const auto hit = impl_->tree.first_intersection(K::Ray_3(point(p), K::Vector_3(d.x(), d.y(), d.z())));
  if (!hit) return std::numeric_limits<double>::infinity();
  const K::Point_3* at = boost::get<K::Point_3>(&hit->first);
  if (!at) return std::numeric_limits<double>::infinity();
  return length - (vec(*at) - p).norm();
}

double PrimitiveShape::signed_distance(const Vec3& x) const {
  const double distance = std::sqrt(impl_->tree.squared_distance(point(x)));
  return radial(x) < 0 ? -distance : distance;
}

bool PrimitiveShape::near(const Vec3& x, double margin) const { return impl_->box.exteriorDistance(x) <= margin; }

std::vector<Index> covered_vertices(const TargetMesh& target, const Primitive& primitive,
                                    const CoverageOptions& options) {
  if (!primitive.fitted) return {};
  const PrimitiveShape shape(primitive);
  const double delta = options.delta * target.scale();
  const std::vector<Vec3>& vertices = target.mesh().vertices;
  std::vector<char> covered(vertices.size(), 0);
  tbb::parallel_for(std::size_t{0}, vertices.size(), [&](std::size_t v) {
    if (!shape.near(vertices[v], delta)) return;
    const double value = options.test == CoverageTest::Radial ? shape.radial(vertices[v])
                                                               : shape.signed_distance(vertices[v]);
    covered[v] = value < delta;
  });
  std::vector<Index> list;
  for (std::size_t v = 0; v < covered.size(); ++v)
    if (covered[v]) list.push_back(static_cast<Index>(v));
  return list;
}

Coverage union_coverage(const TargetMesh& target, const std::vector<std::vector<Index>>& covered_lists) {
  Coverage result;
  result.covered.assign(target.mesh().vertices.size(), 0);
  for (const std::vector<Index>& list : covered_lists)
    for (Index v : list) result.covered[v] = 1;
  // Summed in vertex order, so the energy does not depend on the order of the lists.
  for (std::size_t v = 0; v < result.covered.size(); ++v)
    if (result.covered[v]) result.energy -= target.vertex_areas()[v];
  return result;
}

Coverage coverage(const TargetMesh& target, const std::vector<Primitive>& primitives, const CoverageOptions& options) {
  std::vector<std::vector<Index>> lists(primitives.size());
  tbb::parallel_for(std::size_t{0}, primitives.size(),
                    [&](std::size_t k) { lists[k] = covered_vertices(target, primitives[k], options); });
  return union_coverage(target, lists);
}

}  // namespace medax::msd
