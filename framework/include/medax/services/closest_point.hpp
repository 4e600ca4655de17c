#pragma once
// Closest-point queries on a triangle mesh (CGAL AABB tree).
#include <medax/surface.hpp>

#include <memory>
#include <vector>

namespace medax::services {

struct ClosestPoint {
  Vec3 point;
  Index face = 0;
  double distance = 0;
};

class SurfaceDistance {
 public:
  explicit SurfaceDistance(const SurfaceMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;

  ClosestPoint closest(const Vec3& p) const;
  double distance(const Vec3& p) const { return closest(p).distance; }
  /// Distances of many points, in parallel.
  std::vector<double> distances(const std::vector<Vec3>& points) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace medax::services
