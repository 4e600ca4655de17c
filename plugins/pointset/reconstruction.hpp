#pragma once
// Surface reconstruction from a point cloud, for the stages that need a triangle mesh: CGAL's
// Poisson surface reconstruction (oriented normals; a closed surface) or advancing-front
// surface reconstruction (no normals; interpolates the points, may leave holes).
#include <medax/surface.hpp>

namespace medax::pointset {

enum class ReconstructionMethod { Poisson, AdvancingFront };

struct ReconstructionOptions {
  ReconstructionMethod method = ReconstructionMethod::Poisson;
  /// Poisson: the surface mesher's approximation distance, × the cloud's average spacing
  /// (CGAL's sm_distance; smaller is closer and denser).
  double distance = 0.375;
  /// Poisson: the surface mesher's bound on triangle angles (degrees, CGAL's sm_angle).
  double angle = 20.0;
  /// Advancing front: triangles whose radius ratio exceeds this are not added (CGAL's bound).
  double radius_ratio_bound = 5.0;
};

/// What the reconstruction gave.
struct ReconstructionReport {
  std::size_t border_edges = 0;  ///< edges with one face: 0 for a closed surface
};

/// Reconstructs a triangle mesh of the cloud. Throws std::invalid_argument when Poisson has no
/// normals, and std::runtime_error when CGAL gives no surface (the message says what to try).
SurfaceMesh reconstruct_surface(const OrientedSamples& cloud, const ReconstructionOptions& options,
                                ReconstructionReport* report = nullptr);

}  // namespace medax::pointset
