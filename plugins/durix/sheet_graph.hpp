#pragma once
// The sheet graph of a Durix medial complex (notes §4, connectivity): sheets and curves as
// nodes, their adjacency through singular paths (or, for curves and sheets touching only at a
// medial vertex, through that vertex) as edges. Computed from the output complex's labels
// alone (face `sheet`, `voronoi_face`; edge `path_type`, `sheet`), so it describes exactly what
// the complex says.
#include <medax/medial_complex.hpp>

#include <iosfwd>
#include <vector>

namespace medax::durix {

struct SheetNode {
  int id = 0;
  bool curve = false;               ///< a one-dimensional sheet (chain of degree-0 edges)
  std::size_t polygons = 0;         ///< Voronoi faces (0 for a curve)
  double area = 0;                  ///< total face area (0 for a curve)
  double length = 0;                ///< total curve edge length (0 for a sheet)
  std::size_t boundary_edges = 0;   ///< medial edges of degree 1 on this sheet
  std::size_t medial_vertices = 0;  ///< medial vertices touching the sheet
};

struct SheetAdjacency {
  int a = 0, b = 0;                 ///< a < b
  std::size_t singular_edges = 0;   ///< singular (or forced singular) medial edges both sheets meet at
  std::size_t shared_vertices = 0;  ///< medial vertices both sheets touch
};

struct SheetGraph {
  std::vector<SheetNode> sheets;          ///< by id
  std::vector<SheetAdjacency> adjacency;  ///< sorted by (a, b)
};

/// Throws std::invalid_argument when the complex lacks the durix labels.
SheetGraph sheet_graph(const MedialComplex& medial);

/// JSON: {"sheets": [...], "adjacency": [...]} with lengths and areas multiplied by `scale`
/// and `scale`² (to report them in the input's frame).
void write_sheet_graph_json(std::ostream& out, const SheetGraph& graph, double scale = 1.0);

}  // namespace medax::durix
