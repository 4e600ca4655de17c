#pragma once
// Basic geometric types shared by every stage. Eigen only: no CGAL in public headers.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, rotations: used by nearly every stage
#include <array>
#include <cstdint>

namespace medax {

using Vec3 = Eigen::Vector3d;
using Index = std::uint32_t;
using Tri = std::array<Index, 3>;
using Segment = std::array<Index, 2>;

/// Similarity transform x -> scale * x + offset. Conditioning stages that move the shape record
/// the map back to the input's frame, so outputs can be written in the user's coordinates.
struct Similarity {
  double scale = 1.0;
  Vec3 offset = Vec3::Zero();

  Vec3 apply(const Vec3& x) const { return scale * x + offset; }
  double apply_length(double r) const { return scale * r; }
  /// this ∘ inner: first inner, then this.
  Similarity after(const Similarity& inner) const {
    return {scale * inner.scale, scale * inner.offset + offset};
  }
  Similarity inverse() const { return {1.0 / scale, -offset / scale}; }
};

}  // namespace medax
