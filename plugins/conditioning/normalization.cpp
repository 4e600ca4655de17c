#include "normalization.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace medax::conditioning {

Normalization compute_normalization(const Shape& shape, NormalizeMode mode) {
  const std::vector<Vec3>& points = shape.mesh.vertices.empty() ? shape.samples.points : shape.mesh.vertices;
  if (points.empty()) throw std::invalid_argument("the shape has no vertices and no samples");
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vec3 extent = hi - lo;
  Normalization n;
  n.centre = 0.5 * (lo + hi);
  n.size = mode == NormalizeMode::Diagonal ? extent.norm() : extent.maxCoeff();
  if (!(n.size > 0) || !std::isfinite(n.size))
    throw std::invalid_argument("the shape's bounding box has no extent (all points coincide)");
  return n;
}

void apply_normalization(Shape& shape, const Normalization& n) {
  // Divide rather than multiply by 1/size: the round trip size * ((x - c) / size) + c then
  // returns x to within an ulp or two.
  for (Vec3& v : shape.mesh.vertices) v = (v - n.centre) / n.size;
  for (Vec3& p : shape.samples.points) p = (p - n.centre) / n.size;
  for (double& a : shape.samples.areas) a /= n.size * n.size;
  shape.to_input = shape.to_input.after(n.inverse());
}

}  // namespace medax::conditioning
