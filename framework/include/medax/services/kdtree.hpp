#pragma once
// k-d tree over a point set (nanoflann). The tree refers to the points: keep them alive.
#include <medax/geometry.hpp>

#include <memory>
#include <utility>
#include <vector>

namespace medax::services {

class PointIndex {
 public:
  explicit PointIndex(const std::vector<Vec3>& points);
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;

  /// Index of the nearest point and its distance.
  std::pair<Index, double> nearest(const Vec3& q) const;
  /// The k nearest points, closest first, with distances.
  std::vector<std::pair<Index, double>> k_nearest(const Vec3& q, std::size_t k) const;
  /// Every point within `radius`, closest first, with distances.
  std::vector<std::pair<Index, double>> within(const Vec3& q, double radius) const;
  const std::vector<Vec3>& points() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace medax::services
