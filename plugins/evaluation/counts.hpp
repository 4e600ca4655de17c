#pragma once
// Element counts of a medial complex as MSD (Guo et al. 2024, Table 2) counts them.
#include <medax/medial_complex.hpp>
#include <medax/metrics.hpp>

#include <cstddef>

namespace medax::evaluation {

struct ElementCounts {
  std::size_t vertices = 0;           ///< #v: every medial vertex (sphere)
  std::size_t edges = 0;              ///< distinct edges, triangle sides included
  std::size_t unique_edges = 0;       ///< #e: distinct edges that are no triangle's side
  std::size_t faces = 0;              ///< #f: distinct non-degenerate triangles
  std::size_t isolated_vertices = 0;  ///< vertices in no edge and no triangle

  std::size_t discrete() const { return vertices + unique_edges + faces; }  ///< N_d = #v + #e + #f
  std::size_t continuous() const { return 4 * vertices; }  ///< N_c = 4·#v (centre + radius per sphere)
  Metrics metrics() const;
};

/// Counts after cleaning: duplicate edges/triangles count once, a triangle with a repeated
/// vertex counts as the edge it degenerates to.
ElementCounts count_elements(const MedialComplex& medial);

}  // namespace medax::evaluation
