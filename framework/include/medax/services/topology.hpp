#pragma once
// Topology of a medial complex or a surface mesh seen as a simplicial 2-complex: connected
// components, Euler characteristic and Betti numbers over Z/2.
//
//   b0 = components (union-find over edges and triangle sides),
//   rank ∂1 = #V − b0,
//   rank ∂2 over Z/2 by sparse column reduction, after removing free faces (a triangle with a
//           side that no other remaining triangle has: an elementary collapse, which keeps
//           the rank exact and leaves only the few triangles that can form 2-cycles),
//   b2 = #F − rank ∂2,   b1 = #E − rank ∂1 − rank ∂2,   χ = #V − #E + #F = b0 − b1 + b2.
//
// Elements are cleaned first: edges and triangles are taken as sets of vertices (duplicates
// counted once), a triangle with a repeated vertex counts as the edge it degenerates to, every
// triangle side is an edge whether or not it is listed.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <cstddef>
#include <vector>

namespace medax::services {

struct ComplexTopology {
  std::size_t vertices = 0;  ///< #V (every vertex of the complex, isolated ones included)
  std::size_t edges = 0;     ///< #E: distinct edges, triangle sides included
  std::size_t faces = 0;     ///< #F: distinct non-degenerate triangles
  long long euler = 0;       ///< χ = #V − #E + #F
  std::size_t b0 = 0, b1 = 0, b2 = 0;
  std::size_t components() const { return b0; }
};

/// The complex spanned by `num_vertices` vertices, `edges` and `faces`. Throws
/// std::invalid_argument on an out-of-range vertex index.
ComplexTopology complex_topology(std::size_t num_vertices, const std::vector<Segment>& edges,
                                 const std::vector<Tri>& faces);
ComplexTopology complex_topology(const MedialComplex& medial);

struct SurfaceTopology {
  ComplexTopology complex;            ///< over the vertices used by some face
  std::size_t boundary_edges = 0;     ///< edges with one incident face
  std::size_t nonmanifold_edges = 0;  ///< edges with three or more incident faces
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0; }
  /// Total genus Σ g_i = b0 − χ/2, meaningful for a closed orientable surface (−1 otherwise).
  double genus() const;
};

/// The topology of a triangle mesh. Vertices that no face uses are ignored.
SurfaceTopology surface_topology(const SurfaceMesh& mesh);

}  // namespace medax::services
