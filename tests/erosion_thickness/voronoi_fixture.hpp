#pragma once
// The interior-Voronoi medial complex of a closed mesh's points, from the `voronoi` plugin's core
// (plugins/voronoi/interior_voronoi.hpp), for the tests and benchmarks that need a real complex.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

namespace medax::et::testing {

/// Of the mesh's vertices; generators index them (generator_kind "points").
MedialComplex interior_voronoi_complex(const SurfaceMesh& mesh);
/// The same from other points of the surface (e.g. a subset of its vertices); the generators
/// index `points` (generator_kind "points").
MedialComplex interior_voronoi_complex(const std::vector<Vec3>& points, const SurfaceMesh& mesh);

}  // namespace medax::et::testing
