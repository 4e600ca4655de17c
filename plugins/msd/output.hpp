#pragma once
// What the msd stage hands on (paper §4, Def. 4.2; notes §1, §4): the skeleton as the scene's
// medial complex, every primitive in one PLY, the counts N_d and N_c and msd.json (Ŝ: reconstruction.hpp).
#include "optimisation.hpp"

#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace medax::msd {

/// Skeleton vertex columns: 1 for the optimised sites, 0 for vertices added by construction; ρ0.
inline const Property<int> kIsSite{Element::Vertex, "msd_site"};
inline const Property<double> kInitialRadius{Element::Vertex, "msd_rho0", 1};

/// M_S = (V̂, Ê, F̂) as a medial complex: edges hold only Ê (no triangle side). A vertex's radius
/// is the mean ρ of its vertex primitive, or ρ0 when that primitive failed.
MedialComplex skeleton_complex(const Diagram& diagram);

/// N_d = #v + #e + #f and N_c = Σ|V(T_P)| + 3·#v (paper §6), over fitted primitives.
struct Counts {
  std::size_t vertices = 0, edges = 0, triangles = 0;
  std::size_t discrete = 0;    ///< N_d
  std::size_t continuous = 0;  ///< N_c
  std::size_t failed_primitives = 0;
};
Counts count_elements(const Diagram& diagram);

/// Every fitted primitive in one binary-free ASCII PLY, mapped by `to_input`: per vertex x, y, z,
/// base point bx, by, bz, direction dx, dy, dz and radius; per face its primitive id (the
/// element's index: vertices, then edges, then triangles).
void write_primitives_ply(std::ostream& out, const std::vector<Primitive>& primitives, const Similarity& to_input);

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
  std::string radius_rule;
};
/// msd.json: counts, coverage, compression ratio (3·#v_in + #t_in)/(N_c + N_d), per-phase times
/// (total and per iteration), iterations, rounds, stop reason.
void write_summary_json(std::ostream& out, const Summary& summary);

}  // namespace medax::msd
