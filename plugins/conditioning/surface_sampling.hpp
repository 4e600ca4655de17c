#pragma once
// The `sample` stage's algorithm choice: uniform, Poisson-disk (by count or by radius) or the
// mesh vertices, all with outward unit normals and areas summing to the surface area.
#include <medax/surface.hpp>

#include <random>
#include <string>

namespace medax::conditioning {

enum class SampleMethod { Uniform, Poisson, Vertices };

/// Parses "uniform", "poisson" or "vertices"; throws std::invalid_argument otherwise.
SampleMethod parse_sample_method(const std::string& text);

struct SampleSettings {
  SampleMethod method = SampleMethod::Poisson;
  std::size_t count = 10000;        ///< uniform, and poisson when min_distance is 0
  double min_distance = 0;          ///< poisson: > 0 samples by radius instead of by count
  double oversampling = 5;          ///< poisson: candidates per sample
  double normal_angle_deg = 120;    ///< poisson: samples with normals this far apart never repel
};

/// Throws std::invalid_argument for an empty or zero-area mesh.
OrientedSamples sample_surface(const SurfaceMesh& mesh, const SampleSettings& settings, std::mt19937_64& rng);

}  // namespace medax::conditioning
