#include "target_mesh.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace medax::msd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

std::vector<double> normalised_vertex_areas(const SurfaceMesh& mesh) {
  std::vector<double> areas(mesh.vertices.size(), 0.0);
  double total = 0;
  for (const Tri& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const double area = 0.5 * (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a).norm();
    for (const Index v : f) areas[v] += area / 3.0;
    total += area;
  }
  if (total <= 0) throw std::invalid_argument("the target mesh has zero area; give a closed surface");
  for (double& a : areas) a /= total;
  return areas;
}

double average_edge_length(const SurfaceMesh& mesh) {
  std::set<std::pair<Index, Index>> edges;
  for (const Tri& f : mesh.faces)
    for (int k = 0; k < 3; ++k) edges.emplace(std::minmax(f[k], f[(k + 1) % 3]));
  double sum = 0;
  for (const auto& [a, b] : edges) sum += (mesh.vertices[a] - mesh.vertices[b]).norm();
  return sum / static_cast<double>(edges.size());
}

}  // namespace

struct TargetMesh::Tree {
  Triangles triangles;
  std::vector<Vec3> normals;  ///< unnormalised outward face normals, by face
  AabbTree tree;
};

TargetMesh::TargetMesh(SurfaceMesh mesh) : mesh_(std::move(mesh)), tree_(std::make_unique<Tree>()) {
  if (mesh_.faces.empty()) throw std::invalid_argument("the target mesh has no faces; give a closed triangle mesh");
  vertex_areas_ = normalised_vertex_areas(mesh_);
  mean_edge_length_ = average_edge_length(mesh_);
  Eigen::AlignedBox3d box;
  for (const Vec3& v : mesh_.vertices) box.extend(v);
  scale_ = box.sizes().maxCoeff();
  tree_->triangles.reserve(mesh_.faces.size());
  tree_->normals.reserve(mesh_.faces.size());
  for (const Tri& f : mesh_.faces) {
    const Vec3 &a = mesh_.vertices[f[0]], &b = mesh_.vertices[f[1]], &c = mesh_.vertices[f[2]];
    tree_->triangles.emplace_back(point(a), point(b), point(c));
    tree_->normals.push_back((b - a).cross(c - a));
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

TargetMesh::~TargetMesh() = default;
TargetMesh::TargetMesh(TargetMesh&&) noexcept = default;
TargetMesh& TargetMesh::operator=(TargetMesh&&) noexcept = default;

std::optional<double> TargetMesh::first_exit(const Vec3& origin, const Vec3& direction) const {
  const K::Ray_3 ray(point(origin), K::Vector_3(direction.x(), direction.y(), direction.z()));
  const auto entering = [&](Triangles::const_iterator face) {
    return tree_->normals[static_cast<std::size_t>(face - tree_->triangles.cbegin())].dot(direction) <= 0;
  };
  const auto hit = tree_->tree.first_intersection(ray, entering);
  if (!hit) return std::nullopt;
  if (const K::Point_3* p = boost::get<K::Point_3>(&hit->first))
    return (Vec3(p->x(), p->y(), p->z()) - origin).norm();
  // A ray lying in the face's plane: the normal filter rules that out (normal·d > 0).
  return std::nullopt;
}

double TargetMesh::distance(const Vec3& p) const { return std::sqrt(tree_->tree.squared_distance(point(p))); }

}  // namespace medax::msd
