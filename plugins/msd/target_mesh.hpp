#pragma once
// The input surface S as the MSD fitting and coverage need it (notes §3 S0): the mesh, the
// normalised vertex areas A(v) of Eq. 8, the mean edge length ℓ̄, and two AABB queries (the first
// hit of a ray leaving the shape, the closest distance). The CGAL tree stays in the .cpp.
#include <medax/surface.hpp>

#include <memory>
#include <optional>
#include <vector>

namespace medax::msd {

class TargetMesh {
 public:
  /// S must be closed and outward oriented (the first-hit filter relies on the orientation).
  explicit TargetMesh(SurfaceMesh mesh);
  ~TargetMesh();
  TargetMesh(TargetMesh&&) noexcept;
  TargetMesh& operator=(TargetMesh&&) noexcept;

  const SurfaceMesh& mesh() const { return mesh_; }
  /// A(v): a third of the adjacent triangles' areas over the total area (sums to 1).
  const std::vector<double>& vertex_areas() const { return vertex_areas_; }
  /// ℓ̄: mean length of the unique edges.
  double mean_edge_length() const { return mean_edge_length_; }
  /// Largest side of the bounding box: the length unit of the paper's unit box.
  double scale() const { return scale_; }

  /// Distance along the ray origin + s·direction (direction unit) to its first intersection with
  /// a face whose outward normal has a positive dot product with the direction, i.e. where the
  /// ray leaves the solid; nullopt when there is none.
  std::optional<double> first_exit(const Vec3& origin, const Vec3& direction) const;
  /// Unsigned distance from p to S.
  double distance(const Vec3& p) const;

 private:
  struct Tree;
  SurfaceMesh mesh_;
  std::vector<double> vertex_areas_;
  double mean_edge_length_ = 0;
  double scale_ = 0;
  std::unique_ptr<Tree> tree_;
};

}  // namespace medax::msd
