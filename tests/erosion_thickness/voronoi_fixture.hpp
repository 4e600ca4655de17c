#pragma once
// Test and benchmark stand-in for the `voronoi` extraction (adapted from
// tests/evaluation/voronoi_complex.cpp, so these tests do not wait on the plugin): the
// interior-Voronoi medial complex of a closed mesh's vertices from the Delaunay and inside-test
// services. Vertices: circumcentres of the Delaunay cells whose circumcentre is inside, with their
// circumradii and their 4 cell vertices as generators ("mesh_vertex"). Faces: the Voronoi polygon
// dual to each Delaunay edge whose ring of cells is all interior, fan-triangulated. Edges: the
// faces' sides plus the Voronoi edges between two interior cells.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

namespace medax::et::testing {

MedialComplex interior_voronoi_complex(const SurfaceMesh& mesh);
/// The same from other points of the surface (e.g. a subset of its vertices); the generators
/// index `points` (generator_kind "points").
MedialComplex interior_voronoi_complex(const std::vector<Vec3>& points, const SurfaceMesh& mesh);

}  // namespace medax::et::testing
