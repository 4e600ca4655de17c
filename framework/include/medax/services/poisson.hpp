#pragma once
// Poisson-disk (blue-noise) samples of a triangle mesh, with outward normals and areas.
//
// Both methods start from dense uniform area-weighted candidates (sample_uniform), so they are
// deterministic for a given generator state, whatever the number of threads:
// - by count: weighted sample elimination (Yuksel 2015, "Sample Elimination for Generating
//   Poisson Disk Sample Sets", Eurographics), which returns exactly `count` samples, from the
//   uniform candidates or (faster) from those candidates thinned by parallel dart throwing;
// - by radius: dart throwing over the candidates in their random order, which returns a
//   (nearly maximal) set in which no two samples are closer than `radius`.
// Neighbour searches go through a spatial hash grid, in parallel (TBB); the elimination itself
// is sequential (each removal changes its neighbours' weights).
// Distances are Euclidean, but two samples only repel each other when their normals differ by
// less than `normal_angle_deg`: the two sides of a plate thinner than the radius are sampled
// independently instead of thinning each other out.
#include <medax/surface.hpp>

#include <functional>
#include <random>
#include <string_view>

namespace medax::services {

/// What the elimination by count starts from.
enum class PoissonCandidates {
  /// Yuksel's: `oversampling` × count uniform candidates.
  Uniform,
  /// Those candidates thinned first by dart throwing at 0.65 packing spacings (less where that
  /// keeps fewer than count), in parallel over grid phases, then eliminated down to count: about
  /// three times faster at a million samples, a minimum distance of the darts' radius (0.64-0.65
  /// measured, against Uniform's 0.68-0.70), other samples than Uniform's.
  Darts,
};

struct PoissonDiskOptions {
  /// Uniform candidates drawn per output sample (by count) or per sample of a hexagonal
  /// packing at `radius` (by radius). Yuksel uses 5 for surfaces.
  double oversampling = 5.0;
  /// Samples whose normals differ by this angle or more never repel each other (degrees).
  double normal_angle_deg = 120.0;
  /// By count: the elimination's candidates (by radius: always the uniform ones).
  PoissonCandidates candidates = PoissonCandidates::Uniform;
  /// Called now and then from the calling thread with the fraction done (non-decreasing, 1 at
  /// the end) and the phase (`candidates`, `dart throwing`, `neighbour lists`, `elimination`,
  /// `areas`). It may throw to stop the sampling: the exception leaves the call, nothing else.
  std::function<void(double fraction, std::string_view phase)> progress;
  /// When > 0, at most this many threads (a TBB arena of that size); 0: TBB's default.
  int max_threads = 0;
};

/// Exactly `count` samples by weighted sample elimination (Yuksel 2015). Each sample's area is
/// its Voronoi cell among its 16 nearest samples (with agreeing normals) in its tangent plane,
/// clipped to a disk of 0.75 packing spacings, all scaled so that the areas sum to the surface
/// area. Throws std::invalid_argument for a zero-area mesh or count 0.
OrientedSamples sample_poisson_count(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng,
                                     const PoissonDiskOptions& options = {});

/// Samples no two of which (with agreeing normals) are closer than `radius`, by dart throwing
/// over dense candidates. Areas as above (clipped to 0.75 / 0.7 radii). Throws std::invalid_argument for a zero-area mesh, a
/// radius ≤ 0, or a radius so small that over 50 million candidates would be needed.
OrientedSamples sample_poisson_radius(const SurfaceMesh& mesh, double radius, std::mt19937_64& rng,
                                      const PoissonDiskOptions& options = {});

/// The spacing of an ideal hexagonal packing of `count` points over `area`, 2·sqrt(area /
/// (2·√3·count)): the largest minimum distance `count` samples can have (2·r_max in Yuksel).
double poisson_packing_distance(double area, std::size_t count);

/// The smallest distance between two samples whose normals differ by less than
/// `normal_angle_deg` (infinity when there is no such pair).
double min_sample_distance(const OrientedSamples& samples, double normal_angle_deg = 120.0);

}  // namespace medax::services
