#include "voronoi_fixture.hpp"

#include "interior_voronoi.hpp"

namespace medax::et::testing {

MedialComplex interior_voronoi_complex(const SurfaceMesh& mesh) { return interior_voronoi_complex(mesh.vertices, mesh); }

MedialComplex interior_voronoi_complex(const std::vector<Vec3>& points, const SurfaceMesh& mesh) {
  voronoi::InteriorVoronoiOptions options;
  options.generator_kind = "points";  // indices into `points`
  return voronoi::interior_voronoi(points, mesh, options);
}

}  // namespace medax::et::testing
