#pragma once
// Reconstruction error of a closed surface rebuilt from a medial representation (MSD's Ŝ,
// published as medax/reconstructed_surface.hpp): MSD's vertex-to-surface distances between it and
// the shape, both ways (docs/plugins/evaluation.md).
#include "reconstruction.hpp"

namespace medax::evaluation {

struct RebuiltSurfaceResult {
  double diagonal = 0;  ///< bbox diagonal of the shape (the % normaliser)
  std::size_t surface_samples = 0, rebuilt_samples = 0;
  double rebuilt_area = 0;
  double surface_to_rebuilt_max = 0, surface_to_rebuilt_mean = 0;  ///< over the shape's samples
  double rebuilt_to_surface_max = 0, rebuilt_to_surface_mean = 0;  ///< over the rebuilt surface's samples

  double hausdorff() const { return std::max(surface_to_rebuilt_max, rebuilt_to_surface_max); }
  double eps1() const { return surface_to_rebuilt_mean; }  ///< MSD ε̄¹
  double eps2() const { return rebuilt_to_surface_mean; }  ///< MSD ε̄²
  double eps() const { return std::max(eps1(), eps2()); }  ///< MSD ε̄ (two-sided)
  Metrics metrics() const;
};

/// Measures `rebuilt` (closed, in the shape's current frame) against the shape's mesh (or its
/// samples). Each side is sampled the same way: the vertices its faces use (`use_vertices`) and
/// `uniform_samples` area-uniform points; means are per sample (MSD: "vertex-to-surface").
/// Throws std::invalid_argument when either side has nothing to measure.
RebuiltSurfaceResult measure_rebuilt_surface(const Shape& shape, const SurfaceMesh& rebuilt,
                                             const ReconstructionOptions& options, std::mt19937_64& rng,
                                             const services::CancelCheck& cancel = {});

}  // namespace medax::evaluation
