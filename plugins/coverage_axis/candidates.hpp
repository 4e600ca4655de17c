#pragma once
// Candidate inner balls of Coverage Axis: random interior points (the paper's 20,000) with the
// distance to the surface samples (or the mesh) as radius, or the vertices of a medial complex.
#include "coverage_matrix.hpp"

#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <random>

namespace medax::coverage_axis {

/// Where a random candidate's radius comes from.
enum class RadiusFrom {
  Samples,  ///< distance to the nearest surface sample (the authors' code)
  Mesh      ///< distance to the mesh
};

/// Exactly `count` points uniformly distributed inside the closed mesh: seeded rejection sampling
/// in its bounding box (in batches, classified in parallel, kept in draw order). Throws
/// std::runtime_error when the mesh encloses (almost) no volume.
std::vector<Vec3> random_interior_points(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng);

/// Radii of balls centred at `centres`: distance to the nearest of `samples`, or to the mesh.
std::vector<double> candidate_radii(const std::vector<Vec3>& centres, const SurfaceMesh& mesh,
                                    const std::vector<Vec3>& samples, RadiusFrom from);

/// The complex's vertices with their radii.
Balls complex_balls(const MedialComplex& medial);

}  // namespace medax::coverage_axis
