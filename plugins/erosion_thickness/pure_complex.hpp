#pragma once
// The clean-up that Yan et al. 2016 assume of their input (notes §8, §11.5): a pure 2-complex.
// Vertices closer than a tolerance are welded (the lowest index survives, generators are
// merged), triangles that repeat a vertex or repeat an earlier triangle are dropped, then every
// edge that bounds no triangle and every vertex on no triangle. Vertex fields, labels and
// generators follow their vertices; face properties follow their faces; edge properties are
// dropped (the edges are rebuilt as the sides of the faces).
#include <medax/medial_complex.hpp>

#include <cstddef>

namespace medax::et {

struct PureComplexReport {
  std::size_t welded_vertices = 0;
  std::size_t degenerate_faces = 0;
  std::size_t duplicate_faces = 0;
  std::size_t dangling_edges = 0;    ///< edges that bound no triangle
  std::size_t isolated_vertices = 0; ///< vertices on no triangle (after welding)
  double max_weld_radius_gap = 0;    ///< largest radius difference between welded vertices
};

/// `weld_tolerance` is absolute (0: only exactly coincident centres are welded).
PureComplexReport make_pure_complex(MedialComplex& medial, double weld_tolerance);

}  // namespace medax::et
