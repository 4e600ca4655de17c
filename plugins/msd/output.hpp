#pragma once
// What the msd stage hands on (paper §4, Def. 4.2; notes §1, §4): the skeleton as the scene's
// medial complex, every primitive (fitted or refined) in one PLY, the counts N_d and N_c and
// msd.json (Ŝ: reconstruction.hpp, union_surface.hpp).
#include "optimisation.hpp"
#include "refinement.hpp"

#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace medax::msd {

/// Skeleton vertex columns: 1 for the optimised sites, 0 for vertices added by construction; ρ0.
inline const Property<int> kIsSite{Element::Vertex, "msd_site"};
inline const Property<double> kInitialRadius{Element::Vertex, "msd_rho0", 1};

/// M_S = (V̂, Ê, F̂) as a medial complex: edges hold only Ê (no triangle side). A vertex's radius
/// is the mean ρ of its vertex primitive, or ρ0 when that primitive failed.
MedialComplex skeleton_complex(const Diagram& diagram);

/// N_d = #v + #e + #f and N_c = Σ|V(T_P)| + 3·#v (paper §6), over the final primitives' meshes
/// (refined or fitted; a failed primitive has none).
struct Counts {
  std::size_t vertices = 0, edges = 0, triangles = 0;
  std::size_t discrete = 0;    ///< N_d
  std::size_t continuous = 0;  ///< N_c
  std::size_t failed_primitives = 0;
};
/// Counts with the fitted T_P.
Counts count_elements(const Diagram& diagram);
/// Counts with the final primitives' meshes (aligned with diagram.primitives).
Counts count_elements(const Diagram& diagram, const std::vector<RefinedPrimitive>& final_primitives);

/// The fitted primitives as final ones without refinement (`refined` false, the note says so):
/// T_P's mesh and base points; a failed primitive stays empty. Aligned with `primitives`.
std::vector<RefinedPrimitive> unrefined_primitives(const std::vector<Primitive>& primitives);

/// Every final primitive's mesh in one ASCII PLY, mapped by `to_input`: per vertex x, y, z, base
/// point bx, by, bz, direction dx, dy, dz and radius (vertex = base + radius·direction; both
/// recomputed from the vertex and its base, so general refined meshes fit too) and the S vertex it
/// is (`input_vertex`, -1 for none); per face its primitive id (the element's index: vertices,
/// then edges, then triangles) and whether that primitive was refined.
void write_primitives_ply(std::ostream& out, const std::vector<RefinedPrimitive>& final_primitives,
                          const Similarity& to_input);

/// What the refinement (S7) did, for msd.json.
struct RefinementSummary {
  bool enabled = false;
  std::size_t refined = 0, unrefined = 0;  ///< over fitted primitives
  std::vector<std::pair<std::size_t, std::string>> notes;  ///< primitive id and why it was left unrefined
  double seconds = 0;      ///< wall clock
  double cpu_seconds = 0;  ///< process CPU time (all threads)
};

/// Everything msd.json reports.
struct Summary {
  Counts counts;
  std::size_t input_vertices = 0, input_triangles = 0;
  double covered_area = 0;      ///< −E_cov
  double covered_vertices = 0;  ///< fraction of S's vertices covered
  const OptimisationResult* result = nullptr;
  double seconds_total = 0;
  double seconds_reconstruction = 0;
  std::string reconstruction;  ///< how Ŝ was built, or empty when it was not
  RefinementSummary refinement;
  std::string radius_rule;
};
/// msd.json: counts, coverage, compression ratio (3·#v_in + #t_in)/(N_c + N_d), per-phase times
/// (total and per iteration), iterations, rounds, stop reason, the refinement.
void write_summary_json(std::ostream& out, const Summary& summary);

}  // namespace medax::msd
