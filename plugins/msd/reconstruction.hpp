#pragma once
// Ŝ = ∪ T_P, the reconstruction the paper measures (§6; its SDF reconstruction on a 256³ grid):
// every fitted primitive is rasterised to a narrow-band signed-distance grid, the grids are united
// by their minimum (CSG union) and the zero level set is meshed, all by OpenVDB (kept in the .cpp).
#include "primitive.hpp"

#include <medax/reconstructed_surface.hpp>

#include <vector>

namespace medax::msd {

struct SdfOptions {
  /// Voxels across the longest side of the primitives' bounding box (the paper: 256).
  int resolution = 256;
};

/// The voxel size for `primitives` (fitted ones only): longest bounding-box side / resolution.
double sdf_voxel_size(const std::vector<Primitive>& primitives, const SdfOptions& options);

/// Ŝ in the working frame (closed, outward oriented), `to_input` copied into the result. Primitives
/// that are not fitted are left out. Throws std::invalid_argument when none is fitted.
ReconstructedSurface reconstruct_sdf(const std::vector<Primitive>& primitives, const Similarity& to_input,
                                     const SdfOptions& options = {});

}  // namespace medax::msd
