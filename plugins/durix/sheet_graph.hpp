#pragma once
// The sheet graph of a Durix medial complex (notes §4, connectivity): sheets and curves as
// nodes, their adjacency through singular paths (or, for curves and sheets touching only at a
// medial vertex, through that vertex) as edges. Computed from the output complex's labels
// alone (face `sheet`, `voronoi_face`; edge `path_type`, `sheet`), so it describes exactly what
// the complex says. `durix` publishes it as scene data (kSheetGraph), so a later stage can read
// it and the run folder gets `<id>_sheets.json`.
#include <medax/medial_complex.hpp>
#include <medax/scene_data.hpp>

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
  /// Lengths and areas are in the complex's frame; times input_scale (areas times its square)
  /// they are in the input's frame (`durix` sets it to the shape's to_input.scale).
  double input_scale = 1.0;
};

/// Throws std::invalid_argument when the complex lacks the durix labels.
SheetGraph sheet_graph(const MedialComplex& medial);

/// JSON: {"sheets": [...], "adjacency": [...]} with lengths and areas in the input's frame
/// (multiplied by `input_scale` and its square).
void write_sheet_graph_json(std::ostream& out, const SheetGraph& graph);

/// The sheet graph as scene data: published by `durix`, written as `<id>_sheets.json`.
inline const DataKey<SheetGraph> kSheetGraph{
    "durix.sheet_graph", "durix", "sheets.json",
    [](const SheetGraph& graph, std::ostream& out) { write_sheet_graph_json(out, graph); }};

}  // namespace medax::durix
