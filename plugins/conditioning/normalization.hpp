#pragma once
// Normalisation of a shape to a unit bounding box, keeping the map back to the input frame.
#include <medax/surface.hpp>

#include <string>
#include <utility>
#include <vector>

namespace medax::conditioning {

enum class NormalizeMode {
  Diagonal,  ///< the bounding-box diagonal becomes 1
  MaxSide,   ///< the longest bounding-box side becomes 1
};
/// The name of each mode, as the `normalize` stage's `mode` parameter spells it.
inline const std::vector<std::pair<std::string, NormalizeMode>> kNormalizeModes{{"diagonal", NormalizeMode::Diagonal},
                                                                                {"max_side", NormalizeMode::MaxSide}};

/// The normalisation x -> (x - centre) / size.
struct Normalization {
  Vec3 centre = Vec3::Zero();  ///< bounding-box centre
  double size = 1;             ///< the bounding-box measure that becomes 1
  /// The inverse map, y -> size * y + centre (current frame -> frame before normalising).
  Similarity inverse() const { return {size, centre}; }
};

/// The bounding box of the mesh vertices, or of the samples when there is no mesh. Throws
/// std::invalid_argument when there is nothing to measure or the box has no extent.
Normalization compute_normalization(const Shape& shape, NormalizeMode mode);

/// Moves the mesh and the samples (points, and areas by 1/size²; normals keep) and composes
/// shape.to_input with the inverse map, so to_input still maps the current frame to the input's.
void apply_normalization(Shape& shape, const Normalization& normalization);

}  // namespace medax::conditioning
