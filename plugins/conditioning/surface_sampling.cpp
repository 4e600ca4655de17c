#include "surface_sampling.hpp"

#include <medax/services/poisson.hpp>
#include <medax/services/sampling.hpp>

#include <stdexcept>

namespace medax::conditioning {

OrientedSamples sample_surface(const SurfaceMesh& mesh, const SampleSettings& settings, std::mt19937_64& rng,
                               const std::function<void(double, std::string_view)>& progress) {
  if (mesh.empty()) throw std::invalid_argument("the shape has no surface mesh to sample");
  switch (settings.method) {
    case SampleMethod::Uniform:
      return services::sample_uniform(mesh, settings.count, rng);
    case SampleMethod::Poisson: {
      services::PoissonDiskOptions options = settings.poisson;
      options.progress = progress;
      return settings.min_distance > 0 ? services::sample_poisson_radius(mesh, settings.min_distance, rng, options)
                                       : services::sample_poisson_count(mesh, settings.count, rng, options);
    }
    case SampleMethod::Vertices: {
      // Vertices used by no face (or only by zero-area faces) have no normal: leave them out.
      const OrientedSamples all = services::vertex_samples(mesh);
      OrientedSamples used;
      for (std::size_t i = 0; i < all.size(); ++i) {
        if (!(all.areas[i] > 0)) continue;
        used.points.push_back(all.points[i]);
        used.normals.push_back(all.normals[i]);
        used.areas.push_back(all.areas[i]);
      }
      if (used.empty()) throw std::invalid_argument("the mesh has zero area");
      return used;
    }
  }
  throw std::logic_error("unknown sampling method");
}

}  // namespace medax::conditioning
