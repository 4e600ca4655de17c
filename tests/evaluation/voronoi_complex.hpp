#pragma once
// Benchmark helper: the interior-Voronoi medial complex of a closed mesh's vertices, built from
// the Delaunay and inside-test services (a stand-in for the `voronoi` plugin, so the evaluation
// benchmark does not depend on it). Vertices: circumcentres of the Delaunay cells whose
// circumcentre is inside the mesh, with their circumradii. Faces: the Voronoi polygon dual to
// each Delaunay edge whose ring of cells is all interior, fan-triangulated. Edges: the Voronoi
// edges dual to facets between two interior cells.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

namespace medax::bench {

MedialComplex interior_voronoi_complex(const SurfaceMesh& mesh);

}  // namespace medax::bench
