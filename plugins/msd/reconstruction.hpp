#pragma once
// Ŝ = ∪ T_P by the paper's SDF reconstruction (§6, on a 256³ grid): every primitive's closed
// mesh (the fitted T_P or its refinement) is rasterised to a narrow-band signed-distance grid, the
// grids are united by their minimum (CSG union) and the zero level set is meshed, all by OpenVDB
// (kept in the .cpp). The grid-free union is union_surface.hpp.
#include "primitive.hpp"
#include "refinement.hpp"

#include <medax/reconstructed_surface.hpp>

#include <vector>

namespace medax::msd {

struct SdfOptions {
  /// Voxels across the longest side of the primitives' bounding box (the paper: 256).
  int resolution = 256;
};

/// The closed surfaces Ŝ unites: every fitted T_P (primitives that are not fitted are left out).
std::vector<SurfaceMesh> fitted_surfaces(const std::vector<Primitive>& primitives);
/// Every refined primitive's mesh (one left unrefined is its fitted T_P; empty ones are left out).
std::vector<SurfaceMesh> refined_surfaces(const std::vector<RefinedPrimitive>& refined);

/// The voxel size for `solids`: longest side of their bounding box / resolution (0 for none).
double sdf_voxel_size(const std::vector<SurfaceMesh>& solids, const SdfOptions& options);

/// Ŝ in the working frame (closed, outward oriented), `to_input` copied into the result. `solids`
/// are closed, outward-oriented meshes. Throws std::invalid_argument when they hold no face.
ReconstructedSurface reconstruct_sdf(const std::vector<SurfaceMesh>& solids, const Similarity& to_input,
                                     const SdfOptions& options = {});

}  // namespace medax::msd
