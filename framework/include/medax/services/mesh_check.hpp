#pragma once
// Mesh checks and repair (CGAL Polygon_mesh_processing inside the .cpp files).
//
// check_mesh() works on the mesh as a polygon soup: it never assumes that the faces form a valid
// halfedge structure, so it is safe on broken input (non-manifold edges, repeated corners,
// coincident vertices). repair_mesh() fixes the cheap problems always and the expensive ones
// (holes, self-intersections) only when asked, then checks its own output again: its result says
// what is still wrong, it never hands back a mesh it has not re-checked.
#include <medax/surface.hpp>

#include <optional>
#include <string>
#include <vector>

namespace medax::services {

/// What can be wrong with a surface mesh that should bound a solid.
enum class MeshProblemKind {
  Empty,                    ///< no faces
  Holes,                    ///< boundary edges (one face), grouped in loops
  NonManifoldEdges,         ///< edges with three or more faces
  NonManifoldVertices,      ///< vertices whose faces form two or more fans
  InconsistentOrientation,  ///< two faces run through their shared edge in the same direction
  InwardOrientation,        ///< closed and consistent, but the signed volume is negative
  MisorientedShells,        ///< a closed shell faces the wrong way for its nesting (e.g. an outward
                            ///< shell inside a solid: two overlapping solids, or a cavity facing out)
  SelfIntersections,        ///< triangles meeting outside their shared vertex or edge
  DuplicateVertices,        ///< distinct vertices at exactly the same position
  DegenerateFaces,          ///< repeated corner or collinear corners (zero area)
  DuplicateFaces,           ///< the same three vertices as an earlier face
  UnreferencedVertices,     ///< vertices used by no face
};

struct MeshProblem {
  MeshProblemKind kind;
  /// True when `repair` fixes it by default (duplicates, degenerate faces, orientation,
  /// unreferenced vertices); false when it needs an opt-in repair or a fixed input.
  bool automatic = false;
  /// One line: what is wrong, with counts, and the fix, e.g. "5 boundary loops (holes, 223
  /// boundary edges): run `repair` with fill_holes: true, or close the holes in the mesh".
  std::string message;
};

struct MeshCheckOptions {
  /// The only expensive test (all pairs of triangles with overlapping boxes, exact predicates,
  /// in parallel). When false, `self_intersecting` stays empty.
  bool self_intersections = true;
};

/// Facts about a triangle mesh, computed on the raw soup (nothing merged or repaired).
struct MeshReport {
  std::size_t vertices = 0, faces = 0;
  std::size_t unreferenced_vertices = 0;
  std::size_t duplicate_vertices = 0;  ///< vertices repeating an earlier vertex's position
  std::size_t degenerate_faces = 0;    ///< repeated index or collinear corners
  std::size_t duplicate_faces = 0;     ///< same vertex set as an earlier face
  std::size_t edges = 0;               ///< distinct undirected edges of faces without repeated corners
  std::size_t boundary_edges = 0, boundary_loops = 0;
  std::size_t nonmanifold_edges = 0, nonmanifold_vertices = 0;
  std::size_t inconsistent_edges = 0;
  std::size_t components = 0;  ///< connected components of faces sharing a vertex

  bool closed = false;                  ///< no boundary edge (and at least one face)
  bool manifold = false;                ///< no non-manifold edge or vertex
  bool consistently_oriented = false;   ///< no inconsistent edge
  double signed_volume = 0;             ///< meaningful when closed and consistently oriented; may
                                        ///< under- or overflow at extreme coordinate scales
  /// The signed volume over the cube of the bounding box's longest side: scale-free (computed in
  /// unit coordinates, so exact in sign at 1e-120 or 1e120 too). Decides the orientation.
  double relative_volume = 0;
  bool outward = false;                 ///< closed, consistent and relative volume > 0
  /// Closed, manifold, consistent meshes: components whose orientation does not fit their nesting.
  /// A shell inside an even number of others (0: an outer surface) must face out, one inside an
  /// odd number in (a cavity). Containment by generalized winding number.
  std::size_t misoriented_shells = 0;

  long long euler_characteristic = 0;   ///< V − E + F over referenced vertices
  /// Only for closed manifold meshes: the sum of (2 − χ_c)/2 over components, and per component
  /// (components in the order of their lowest face index).
  std::optional<long long> genus;
  std::vector<long long> genus_per_component;

  /// Empty when the test was not run (MeshCheckOptions::self_intersections = false).
  std::optional<bool> self_intersecting;
  std::size_t intersecting_pairs = 0;  ///< pairs of non-degenerate triangles that intersect
  std::size_t intersecting_faces = 0;  ///< faces in at least one such pair

  double seconds = 0;                     ///< time of the whole check
  double self_intersection_seconds = 0;   ///< of which the self-intersection test

  /// Every problem found, serious ones first, one line each with its fix.
  std::vector<MeshProblem> problems() const;
  /// The problems as text, one line per problem (empty when there is none).
  std::string describe_problems() const;
  /// True when there is no problem: closed, manifold, consistently and outward oriented, free of
  /// self-intersections (when tested), duplicates, degenerate faces and unreferenced vertices.
  bool ok() const { return problems().empty(); }
  /// What a solid needs (and what the `repair` stage requires): at least one face, closed,
  /// manifold, consistently and outward oriented (every shell as its nesting says), and free of
  /// self-intersections when tested.
  /// Duplicate vertices, degenerate faces and unreferenced vertices are tolerated here.
  bool valid_solid() const;
  /// One line of facts for logs: "26002 vertices, 52000 faces, closed, manifold, genus 0, ...".
  std::string summary() const;
};

/// Checks a triangle mesh without changing it. Never throws on bad topology; throws
/// std::invalid_argument only when a face refers to a vertex that does not exist.
MeshReport check_mesh(const SurfaceMesh& mesh, const MeshCheckOptions& options = {});

struct RepairOptions {
  /// Close every boundary loop (CGAL triangulate_refine_and_fair_hole, or a flat refined
  /// triangulation when `fair_holes` is false).
  bool fill_holes = false;
  bool fair_holes = true;
  /// Loops with more boundary edges are left open (and reported); 0 means no limit.
  std::size_t max_hole_edges = 0;
  /// Remove self-intersections: CGAL autorefine_and_remove_self_intersections (exact: refines the
  /// mesh along the intersections and drops the parts inside), then, for what remains,
  /// CGAL's local remove_self_intersections (smoothing / hole filling).
  bool remove_self_intersections = false;
  /// Run the self-intersection test in the checks (before and after). Turning it off makes
  /// repair fast on big meshes but blind to self-intersections.
  bool check_self_intersections = true;
};

struct RepairResult {
  SurfaceMesh mesh;  ///< the repaired mesh (compact: no unreferenced vertex)
  MeshReport before;  ///< check of the input
  MeshReport after;   ///< check of `mesh`
  std::vector<std::string> actions;   ///< what was done, one line each, for the log
  std::vector<std::string> failures;  ///< repairs that were tried and failed, one line each
  bool changed = false;               ///< `mesh` differs from the input
  /// The re-check passes: `after.valid_solid()`.
  bool ok() const { return after.valid_solid(); }
};

/// Merges duplicate vertices, drops repeated-corner, duplicate and (by edge collapse)
/// collinear faces and unreferenced vertices, orients the faces consistently and outward
/// (CGAL orient_polygon_soup, orient_to_bound_a_volume), splits non-manifold vertices and edges
/// (the surface cannot be stored otherwise), then applies the opt-in repairs, then checks the
/// result again. Never throws on bad input: inspect `after` and `failures`.
RepairResult repair_mesh(const SurfaceMesh& mesh, const RepairOptions& options = {});

}  // namespace medax::services
