#pragma once
// Global optimisation of the Medial Skeletal Diagram (paper §5.3, Eq. 8, Alg. 1; notes §2.7,
// §3 S2, S5, S6, §9.5–9.6): sites on the medial mesh M start at a farthest-point selection on M's
// graph distances; Nelder–Mead (NLopt) moves the free sites to minimise
//   E = E_cov + c1 E_cent + c2 E_count,
// each trial point projected onto M, the skeleton constructed (S3) and every element fitted (S4,
// fits of unchanged elements cached); between rounds, new free sites are put at the volume
// centres of the largest uncovered regions of S and the old ones frozen.
#include "construction.hpp"
#include "coverage.hpp"
#include "fitting.hpp"
#include "medial_mesh.hpp"
#include "target_mesh.hpp"

#include <functional>
#include <string>
#include <vector>

namespace medax::msd {

/// How a trial point becomes a site on M.
enum class Projection {
  ClosestPoint,   ///< the closest point of M (paper, Alg. 1)
  FacetCentroid,  ///< the centroid of M's closest facet; two sites on one facet are rejected ([C])
};

/// How δ of E_cov is set.
enum class DeltaRule {
  Value,           ///< CoverageOptions::delta as given (paper: 1e-4 of the unit box)
  MeanEdgeLength,  ///< δ = ℓ̄, the mean edge length of S (what the authors' code effectively uses)
};

struct OptimisationOptions {
  std::size_t initial_sites = 10;   ///< |V⁽⁰⁾| (paper: 10)
  std::size_t start_vertex = 0;     ///< first farthest-point vertex of M ([C]: 0)
  double centroid_weight = 1;       ///< c1
  double count_weight = 1e-3;       ///< c2
  Projection projection = Projection::ClosestPoint;
  double min_site_distance = 1e-2;  ///< sites closer than this (unit box) reject the trial ([C])
  int first_iterations = 50;        ///< energy evaluations of the first round
  int add_every = 30;               ///< energy evaluations of every later round
  std::size_t add_count = 3;        ///< sites added per round (paper: 3 or 5)
  int stall = 5;                    ///< evaluations without decrease that end a round
  int max_iterations = 300;         ///< energy evaluations in all
  double xtol = 1e-2;               ///< Nelder–Mead xtol_abs (unit box)
  /// TetGen switches for the uncovered-volume tets. [C] uses "pq1.05", which did not finish in
  /// 100 s on hand.obj (TetGen 1.5); "pq2" takes 8 s there.
  std::string tetgen_switches = "pq2";
  DeltaRule delta_rule = DeltaRule::MeanEdgeLength;
  FitOptions fit;  ///< the final fit of the best diagram
  /// While optimising, the fit uses `fit` with these two changed: [C] drops the smoothness
  /// there; a coarser template keeps an energy evaluation near a second on 2 cores.
  double search_smoothness = 0;
  std::size_t search_sphere_vertices = 400;
  CoverageOptions coverage;
  ConstructionOptions construction;
};

/// The terms of Eq. 8 for one site set.
struct Energy {
  double total = 0;
  double coverage = 0;  ///< E_cov ∈ [−1, 0]
  double centroid = 0;  ///< E_cent = Σ ‖v − c(RVC(v))‖² in unit-box units
  double count = 0;     ///< E_count = |V̂| − |V|
  bool rejected = false;
  std::string rejection;  ///< why (sites too close, one facet, construction failed)
};

/// One evaluated site set: the diagram and its energy.
struct Diagram {
  std::vector<Vec3> sites;  ///< on M
  Skeleton skeleton;
  std::vector<SkeletonElement> elements;  ///< V̂, then Ê, then F̂
  std::vector<Primitive> primitives;      ///< one per element, same order
  Coverage coverage;
  Energy energy;
};

/// What Table 1 reports, per energy evaluation.
struct IterationLog {
  int iteration = 0;  ///< energy evaluations so far (1-based)
  int round = 0;
  std::size_t sites = 0;
  std::size_t fitted = 0;  ///< primitives fitted (not from the cache)
  Energy energy;
  double best = 0;  ///< best energy so far
  double seconds_projection = 0, seconds_construction = 0, seconds_fitting = 0, seconds_energy = 0;
};

/// What happened between two rounds.
struct RoundLog {
  std::size_t uncovered_regions = 0;
  std::size_t sites_added = 0;
  double largest_region_volume = 0;
  double seconds = 0;  ///< coverage of the tets and ranking (tetrahedralisation excluded)
};

struct OptimisationResult {
  Diagram best;
  std::vector<IterationLog> log;
  std::vector<RoundLog> additions;
  int rounds = 0;
  std::string stop_reason;
  double seconds_tetrahedralisation = 0;
  std::size_t tets = 0;
  double delta = 0;  ///< δ used, in units of TargetMesh::scale()
  double seconds_final_fit = 0;
};

/// The options with δ set by `delta_rule` for this S.
OptimisationOptions resolve_delta(const OptimisationOptions& options, const TargetMesh& target);

/// The fit options of an energy evaluation (`fit` with the search smoothness and template size).
FitOptions search_fit_options(const OptimisationOptions& options);

/// The skeleton's elements: every vertex, every unique edge, every triangle.
std::vector<SkeletonElement> skeleton_elements(const Skeleton& skeleton);

/// Projects points onto M as `projection` says.
std::vector<Vec3> project_sites(const MedialMesh& medial, const std::vector<Vec3>& points, Projection projection);

/// Evaluates Eq. 8 for site sets, keeping fits of unchanged elements and the vertices they cover
/// between calls.
class EnergyEvaluator {
 public:
  EnergyEvaluator(const TargetMesh& target, const MedialMesh& medial, const SurfaceCrossing& crossing,
                  const OptimisationOptions& options);
  ~EnergyEvaluator();
  /// Sites = frozen ∪ project(free); fills `log`'s timings and counts when given.
  Diagram evaluate(const std::vector<Vec3>& frozen, const std::vector<Vec3>& free, IterationLog* log = nullptr);
  /// Drops cached fits not used by the last two evaluations nor by `keep`.
  void trim_cache(const Diagram& keep);

 private:
  std::vector<Primitive> fit(const std::vector<SkeletonElement>& elements, std::size_t& fitted);
  /// Each element's covered vertices of S, computed once per cached fit.
  std::vector<std::vector<Index>> covered_lists(const std::vector<SkeletonElement>& elements);
  struct Cache;
  const TargetMesh& target_;
  const MedialMesh& medial_;
  const SurfaceCrossing& crossing_;
  OptimisationOptions options_;
  std::unique_ptr<Cache> cache_;
};

/// E_cent: squared distances of the sites to the centroids of their restricted Voronoi cells.
double centroid_energy(const std::vector<Vec3>& sites, const std::vector<RvdPiece>& pieces);

/// The whole schedule (S2, S5, S6). `on_iteration` is called after every energy evaluation;
/// `cancelled` is polled there and ends the run by throwing medax::Cancelled.
OptimisationResult optimise(const TargetMesh& target, const MedialMesh& medial, const OptimisationOptions& options,
                            const std::function<void(const IterationLog&)>& on_iteration = {},
                            const std::function<bool()>& cancelled = {});

}  // namespace medax::msd
