#pragma once
// The `sample` stage's algorithm choice: uniform, Poisson-disk (by count or by radius) or the
// mesh vertices, all with outward unit normals and areas summing to the surface area.
#include <medax/services/poisson.hpp>
#include <medax/surface.hpp>

#include <functional>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace medax::conditioning {

enum class SampleMethod { Uniform, Poisson, Vertices };
/// The name of each method, as the `sample` stage's `method` parameter spells it.
inline const std::vector<std::pair<std::string, SampleMethod>> kSampleMethods{
    {"poisson", SampleMethod::Poisson}, {"uniform", SampleMethod::Uniform}, {"vertices", SampleMethod::Vertices}};

/// The name of each choice of the elimination's candidates, as the `candidates` parameter spells it.
inline const std::vector<std::pair<std::string, services::PoissonCandidates>> kPoissonCandidates{
    {"uniform", services::PoissonCandidates::Uniform}, {"darts", services::PoissonCandidates::Darts}};

struct SampleSettings {
  SampleMethod method = SampleMethod::Poisson;
  std::size_t count = 10000;  ///< uniform, and poisson when min_distance is 0
  double min_distance = 0;    ///< poisson: > 0 samples by radius instead of by count
  services::PoissonDiskOptions poisson;  ///< poisson: oversampling, candidates, normal angle
};

/// Throws std::invalid_argument for an empty or zero-area mesh. Poisson-disk sampling reports
/// to `progress` (PoissonDiskOptions::progress), which may throw to stop it.
OrientedSamples sample_surface(const SurfaceMesh& mesh, const SampleSettings& settings, std::mt19937_64& rng,
                               const std::function<void(double, std::string_view)>& progress = {});

}  // namespace medax::conditioning
