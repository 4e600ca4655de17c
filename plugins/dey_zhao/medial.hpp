#pragma once
// MEDIAL (Dey & Zhao 2004, "Approximating the medial axis from the Voronoi diagram with a
// convergence guarantee", Algorithmica 38): the medial axis as the Voronoi facets dual to the
// Delaunay edges that pass the Angle or the Ratio condition at one of their ends, plus their
// closure. Plain C++ over the medax data model; the `dey_zhao` stage is a thin face of it.
// Realisation: the global passes A–F of docs/notes/dey_zhao2004.md §2.3 (see
// docs/plugins/dey_zhao.md for every choice and deviation).
#include <medax/medial_complex.hpp>
#include <medax/services/delaunay.hpp>
#include <medax/surface.hpp>

#include <string>
#include <utility>
#include <vector>

namespace medax::dey_zhao {

inline constexpr double kPi = 3.14159265358979323846;

/// Which selected facets are kept: the paper keeps those whose dual Delaunay edge is enclosed by
/// an interpolating watertight surface (TIGHT COCONE); notes §2.6 (a)–(c), or no selection.
enum class InnerSelection {
  Auto,             ///< DelaunaySurface when it applies, else Mesh, else Normals, else None
  DelaunaySurface,  ///< (a) mesh triangles are Delaunay facets: cells flooded with wall parity
  Mesh,             ///< (b) edge midpoint strictly inside the mesh, segment not crossing it
  Normals,          ///< (c) the edge leaves both ends inwards: t_pq·n_p < 0 and t_qp·n_q < 0
  None,             ///< inner and outer medial axis (the paper's ENGINE)
};
/// The name of each inner selection: the `inner` parameter's choices, and to_string().
const std::vector<std::pair<std::string, InnerSelection>>& inner_selection_names();
const char* to_string(InnerSelection s);

/// What happens to a selected facet dual to a convex-hull edge (an unbounded Voronoi facet).
enum class Unbounded {
  Drop,  ///< not output (counted)
  Clip,  ///< its two rays truncated at clip_factor × bbox diagonal, closed by a chord
};

struct MedialOptions {
  bool angle_condition = true;
  double theta = kPi / 8;  ///< Angle condition [θ]: radians
  bool ratio_condition = true;
  double rho = 8;  ///< Ratio condition [ρ]
  InnerSelection inner = InnerSelection::Auto;
  Unbounded unbounded = Unbounded::Drop;
  double clip_factor = 2.0;        ///< ray length, in bounding-box diagonals of the points
  double merge_tolerance = 1e-12;  ///< facet vertices closer than this × bbox diagonal are merged
  std::string generator_kind = "mesh_vertex";  ///< what the point indices refer to
  bool parallel = true;
};

/// The data MEDIAL reads. Only `points` is needed by the algorithm; the mesh and the normals
/// serve the inner/outer selection only.
struct MedialInput {
  const std::vector<Vec3>* points = nullptr;
  const std::vector<Vec3>* normals = nullptr;  ///< outward unit normal per point (Normals)
  const SurfaceMesh* mesh = nullptr;           ///< closed surface (Mesh, DelaunaySurface)
  bool points_are_mesh_vertices = false;       ///< `points` is mesh->vertices (DelaunaySurface)
};

/// What the extraction did, for logs, tests and benchmarks.
struct MedialReport {
  std::size_t points = 0;          ///< distinct points in the Delaunay tetrahedralization
  std::size_t cells = 0;           ///< finite Delaunay cells
  std::size_t delaunay_edges = 0;  ///< finite Delaunay edges (from Euler's relation)
  std::size_t hull_points = 0;     ///< points with an unbounded Voronoi cell
  std::size_t empty_umbrellas = 0; ///< points whose umbrella is empty (they select nothing)
  std::size_t selected = 0;        ///< edges passing a condition at one end
  std::size_t selected_angle = 0;  ///< ... of which passing the Angle condition (at p or q)
  std::size_t selected_ratio = 0;  ///< ... of which passing the Ratio condition (at p or q)
  std::size_t unbounded = 0;       ///< selected edges whose dual facet is unbounded
  std::size_t unbounded_dropped = 0;
  std::size_t outer = 0;           ///< bounded-or-clipped selected edges the inner selection rejected
  std::size_t facets = 0;          ///< Voronoi facets output (including degenerate ones)
  std::size_t degenerate_facets = 0;  ///< facets that merge into a point or a segment
  std::size_t merged_vertices = 0;    ///< facet vertices merged into another (merge_tolerance)
  InnerSelection inner_used = InnerSelection::None;
  std::string inner_note;  ///< why `Auto` chose what it chose
  double seconds_delaunay = 0;   ///< Delaunay tetrahedralization (overlapping the inner-test setup)
  double seconds_umbrellas = 0;  ///< passes B–C: poles and umbrellas
  double seconds_filter = 0;     ///< passes D–E: conditions on every edge, rings of the selected
  double seconds_inner = 0;      ///< pass F: the inner/outer selection
  double seconds_complex = 0;    ///< the output complex
  double seconds_filtering() const { return seconds_umbrellas + seconds_filter + seconds_inner + seconds_complex; }
};

/// Poles and umbrellas of every point (passes B and C).
struct Umbrellas {
  std::vector<Vec3> pole_vector;  ///< unit v_p (sign irrelevant); zero when undefined
  std::vector<char> on_hull;      ///< V_p unbounded: v_p is the normalised sum of hull normals
  /// Umbrella of point x: slots offsets[x] .. offsets[x + 1] of `normals` (and `triangles`).
  std::vector<std::size_t> offsets;
  std::vector<Vec3> normals;       ///< unit normal of each umbrella triangle
  std::vector<Tri> triangles;      ///< its point indices (only when asked for)
  std::vector<double> max_radius;  ///< per point, largest circumradius of its umbrella triangles

  std::size_t size(Index x) const { return offsets[x + 1] - offsets[x]; }
};

/// Passes B–C on a tetrahedralization of `points`. `keep_triangles` fills `triangles` (tests).
Umbrellas compute_umbrellas(const std::vector<Vec3>& points, const services::DelaunayTetrahedralization& dt,
                            bool keep_triangles = false, bool parallel = true);

/// Scores of a Delaunay edge (p, q) at both ends (notes §2.5). `sin_angle_x` = min over the
/// umbrella triangles of x of |n·t̂_pq| (the sine of the smallest angle between pq and their
/// planes), `ratio_x` = |pq| / max circumradius; both −1 when x's umbrella is empty.
struct EdgeScores {
  double sin_angle_p = -1, sin_angle_q = -1, ratio_p = -1, ratio_q = -1;
};
EdgeScores score_edge(const std::vector<Vec3>& points, const Umbrellas& umbrellas, Index p, Index q);

/// Condition bits of a face (label `conditions`).
enum ConditionBit : int { kAngleP = 1, kAngleQ = 2, kRatioP = 4, kRatioQ = 8 };
/// The condition bits an edge with these scores passes under `options` (0: not selected).
int conditions(const EdgeScores& s, const MedialOptions& options);

/// The columns medial_axis() writes (see below).
inline const Property<int> kPolygon{Element::Face, "polygon"};
inline const Property<int> kDualP{Element::Face, "p"};
inline const Property<int> kDualQ{Element::Face, "q"};
inline const Property<int> kConditions{Element::Face, "conditions"};
inline const Property<int> kUnbounded{Element::Face, "unbounded"};
inline const Property<double> kAngle{Element::Face, "angle"};
inline const Property<double> kRatio{Element::Face, "ratio"};
inline const Property<int> kFanDiagonal{Element::Edge, "fan_diagonal"};
inline const Property<int> kClipped{Element::Edge, "clipped"};

/// MEDIAL on `input.points`:
/// - vertices: the circumcentres of the Delaunay cells around the selected edges (radius =
///   circumradius; generators = the cell's 4 corners, sorted), plus, with Unbounded::Clip, the
///   clipped ends of rays (generators = the 3 corners of their hull facet);
/// - faces: each selected facet fan-triangulated from its first vertex, oriented with its normal
///   along p → q; face labels `polygon` (facet number), `p`, `q` (the dual Delaunay edge,
///   p < q), `conditions` (ConditionBit), `unbounded`; face fields `angle` (radians) and `ratio`,
///   the larger of the two ends' scores (ends with an empty umbrella left out);
/// - edges: the facets' Voronoi edges and fan diagonals (edge label `fan_diagonal`), and with
///   Clip the truncated rays and closing chords (edge label `clipped`), sorted, each once.
/// Deterministic; scaling the points by a power of two scales the output exactly.
/// Throws std::invalid_argument when the points span less than 3D, or when the requested inner
/// selection lacks its data (a closed mesh, normals, or Delaunay mesh triangles).
MedialComplex medial_axis(const MedialInput& input, const MedialOptions& options = {},
                          MedialReport* report = nullptr);

}  // namespace medax::dey_zhao
