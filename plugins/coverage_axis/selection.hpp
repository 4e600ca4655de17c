#pragma once
// What the coverage_axis stage hands on: the selected spheres and how they were found (scene
// data, written as `<id>_coverage_axis.json`), and the `selected` vertex column of the complex
// that the qmat stage keeps through its collapse.
#include <medax/medial_complex.hpp>
#include <medax/properties.hpp>
#include <medax/scene_data.hpp>

#include <iosfwd>
#include <string>

namespace medax::coverage_axis {

/// The selected spheres and the solve's record.
struct Selection {
  std::string mode;                  ///< "exact" or "greedy"
  std::string candidates;            ///< "random" or "voronoi"
  std::vector<Vec3> centres;         ///< in the scene's frame (after `normalize`)
  std::vector<double> radii;         ///< undilated
  std::size_t samples = 0;           ///< surface samples drawn
  std::vector<Vec3> sample_points;   ///< the samples (not written to the JSON)
  std::size_t uncovered = 0;         ///< samples no dilated candidate covers (dropped)
  std::size_t candidate_count = 0;   ///< candidates before geometric dominance
  std::size_t undominated = 0;       ///< candidates after geometric dominance (exact mode)
  double dilation = 0;               ///< δ_r in the scene's frame
  std::size_t objective = 0;         ///< |selection|
  double lp_bound = 0;               ///< exact mode: forced + LP relaxation
  double lower_bound = 0;            ///< exact mode: best proven lower bound
  bool proven_optimal = false;       ///< exact mode: CBC proof or LP certificate
  double gap = 0;                    ///< exact mode: (size − ⌈lower bound⌉) / size
  std::size_t greedy = 0;            ///< exact mode: textbook greedy cover size
  std::size_t warm_start = 0;        ///< exact mode: the greedy cover after local search, given to CBC
  std::size_t nodes = 0;             ///< exact mode: branch-and-cut nodes
  std::size_t forced = 0, dominated_columns = 0, dominated_rows = 0;  ///< presolve
  std::size_t rows = 0, columns = 0, nonzeros = 0;  ///< exact mode: the program after presolve
  double seconds_candidates = 0, seconds_matrix = 0, seconds_presolve = 0, seconds_lp = 0, seconds_search = 0,
         seconds_solve = 0;
  std::size_t marked = 0;            ///< complex vertices marked `selected`
};

void write_selection_json(std::ostream& out, const Selection& selection);

/// Published by `coverage_axis`, written as `<id>_coverage_axis.json`.
inline const DataKey<Selection> kSelection{
    "coverage_axis.selection", "coverage_axis", "coverage_axis.json",
    [](const Selection& selection, std::ostream& out) { write_selection_json(out, selection); }};

/// Vertex column: 1 on the complex vertex each selected sphere snapped to, 0 elsewhere.
inline const Property<int> kSelected{Element::Vertex, "selected"};

/// For each centre in order, marks the nearest not yet marked vertex of `medial` (by centre
/// distance; lowest index on ties) in the `selected` column, which it creates or resets. Returns
/// the number marked (fewer than the centres only when the complex has fewer vertices).
std::size_t mark_nearest_vertices(MedialComplex& medial, const std::vector<Vec3>& centres);

}  // namespace medax::coverage_axis
