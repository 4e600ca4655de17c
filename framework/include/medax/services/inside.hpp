#pragma once
// Inside/outside tests against a closed, outward-oriented triangle mesh.
#include <medax/surface.hpp>

#include <memory>
#include <vector>

namespace medax::services {

/// Ray-casting classification with CGAL::Side_of_triangle_mesh over an AABB tree (exact
/// predicates). Build once, query many times; queries are thread-safe.
class InsideTest {
 public:
  explicit InsideTest(const SurfaceMesh& mesh);
  ~InsideTest();
  InsideTest(InsideTest&&) noexcept;
  InsideTest& operator=(InsideTest&&) noexcept;

  /// True when p is strictly inside (points on the boundary count as outside).
  bool inside(const Vec3& p) const;
  /// Classifies many points, in parallel.
  std::vector<char> inside(const std::vector<Vec3>& points) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Generalized winding number of a closed mesh at p (Jacobson et al. 2013): 1 inside, 0
/// outside for a closed outward mesh; robust to small holes. O(#faces) per query.
double winding_number(const SurfaceMesh& mesh, const Vec3& p);

}  // namespace medax::services
