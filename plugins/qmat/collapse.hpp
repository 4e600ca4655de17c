#pragma once
// Q-MAT simplification (Li et al. 2015; notes qmat_coverage_axis.md §1, §2.6): collapse the
// edges of a medial complex in order of (E + k)·γ², E the slab quadric error of the optimal
// sphere, γ the stability ratio, until a target vertex count or a cost bound.
#include "collapse_mesh.hpp"

#include <medax/medial_complex.hpp>

#include <functional>
#include <string>
#include <vector>

namespace medax::qmat {

/// The extra quadrics of faceless edges (notes §1.3).
enum class ConeTerms {
  QmatCode,  ///< the authors' pseudo-slab (m₀, m₁, (c₀ + c₁, (r₀ + r₁)/2)) and its side planes
  Clean,     ///< the cone's tangent planes in four directions 90° apart (unit normals)
};

struct QmatOptions {
  std::size_t target_vertices = 0;  ///< stop at this many vertices (0: no count target)
  double max_cost = 0;              ///< stop before a collapse dearer than this (0: no bound)
  double stability_weight = 1e-5;   ///< k in (E + k)·γ²
  double boundary_weight = 0.1;     ///< β of the sheet-boundary terms (weight 0.1·β·γ²)
  ConeTerms cone_terms = ConeTerms::QmatCode;
  bool flip_test = true;            ///< refuse optimal spheres that flip an incident face
  bool topology_guard = true;       ///< QMAT's hole and curve-tip guard (notes §1.6)
  std::size_t guard_below = 100;    ///< the guard acts once this few vertices remain
  bool link_condition = false;      ///< also require the link condition (keeps the homotopy type)
  bool stale_saved_costs = false;   ///< parity: cost the queue before marking saved vertices
  double unit_length = 0;           ///< normalising length (0: bbox diagonal of the spheres)
  bool parallel = true;             ///< cost the first queue in parallel (same result either way)
};

/// Quadrics before any collapse: the slab terms Q_v and the boundary/cone "add" terms, the
/// latter only for the vertices that have some (a zero quadric adds nothing, bit for bit).
struct InitialQuadrics {
  static constexpr Index kNoAdd = static_cast<Index>(-1);
  std::vector<PackedQuadric> slab;  ///< per vertex
  std::vector<SlabQuadric> add;     ///< the nonzero add terms, in vertex order
  std::vector<Index> add_of;        ///< per vertex: its entry in `add`, or kNoAdd
  std::size_t invalid_faces = 0;    ///< faces without slab planes (close centres, no tangent plane)
};
InitialQuadrics initial_quadrics(const CollapseMesh& mesh, const QmatOptions& options);

struct QmatReport {
  std::size_t initial_vertices = 0, final_vertices = 0, collapses = 0, saved = 0;
  std::size_t invalid_faces = 0, dropped = 0;  ///< dropped: edges the topology checks refused
  double last_cost = 0;                         ///< priority of the last collapse
  std::string stopped_by;                       ///< "target", "max_cost", "queue"
  double seconds_setup = 0, seconds_collapse = 0;
};

/// The simplified complex. `saved` (empty, or one flag per vertex) marks vertices that never
/// move (notes §2.6). Vertex columns follow the surviving vertex (a saved one when there is
/// one, else the lower index), face columns their faces; edges get fresh rows.
MedialComplex simplify(const MedialComplex& medial, const std::vector<char>& saved, const QmatOptions& options,
                       QmatReport* report = nullptr, const std::function<void(double)>& progress = {});

/// The unit QMAT normalises by when options.unit_length is 0: the bbox diagonal of the balls.
double default_unit_length(const MedialComplex& medial);

}  // namespace medax::qmat
