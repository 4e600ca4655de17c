#pragma once
// VMAS — Dynamic Skeletonization via Variational Medial Axis Sampling (Huang, Kraemer, Thery,
// Bechmann, SIGGRAPH Asia 2024), as a library with dynamic edits.
//
//   auto input = vmas::VmasInput::from_mesh(mesh);          // precompute once
//   vmas::VmasOptions options;
//   options.target_spheres = 80;
//   vmas::VmasSolver solver(input, options);                  // starts from the largest shrinking ball
//   solver.run();                                             // partition / update / correct / split
//   auto id = solver.nearest_sphere({0.1, 0.2, 0.3});
//   solver.split_sphere(id);                                  // edit: one more sphere, here
//   for (int i = 0; i < 10; ++i) solver.relax();              // continue from the current state
//   solver.finish();
//   MedialComplex mc = solver.complex(/*connect=*/true);
//
// Every length is in the input's frame; thresholds are relative to the input's largest bounding
// box side ("scale"), as the paper's are to a unit box: an error threshold t means t·scale².
// Sphere ids are stable across edits, splits and culls (a culled or removed id disappears).
#include "dual.hpp"
#include "input.hpp"
#include "partition.hpp"
#include "update.hpp"

#include <medax/medial_complex.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace medax::vmas {

enum class StopMode { Count, Error };
/// When spheres are projected back onto the medial axis (notes §2.6).
enum class Correction {
  Always,   ///< after every update (the authors' default)
  OnSplit,  ///< before every split round and at the end (the authors' CORRECT_ON_SPLIT)
  End,      ///< once, at the end (paper Fig. 11, blue)
  Off,      ///< never
};

/// Which spheres an iteration updates (Gauss–Newton + correction).
enum class UpdateScope {
  Local,  ///< those whose cluster changed at this partition, new ones, and those whose last
          ///< Gauss–Newton solve hit the iteration cap; the others keep their exact values
  Full,   ///< every sphere, every iteration
};

/// When the stop test runs in an iteration (notes §2.10).
enum class StopTest {
  BeforeSplit,  ///< converged with the target met, before any split round (the paper, the CGAL port)
  AfterSplit,   ///< after the split round (the CGoGN code): a round on convergence that reaches the
                ///< target ends the run, its new spheres as split (unoptimised)
};

/// The first sphere (notes §2.8).
enum class InitialSphere {
  LargestBall,  ///< the largest per-vertex shrinking ball (the CGoGN code)
  BoxCorner,    ///< centre at the bounding box's min corner, radius = scale (the CGAL port's
                ///< ((0,0,0), 1) on a unit box)
};

/// The name of each choice, as the `vmas` stage's parameters and the log spell it.
inline const std::vector<std::pair<std::string, StopMode>> kStopModes{{"count", StopMode::Count},
                                                                      {"error", StopMode::Error}};
inline const std::vector<std::pair<std::string, SqemRows>> kSqemRows{{"paper", SqemRows::Paper},
                                                                      {"author_code", SqemRows::AuthorCode}};
inline const std::vector<std::pair<std::string, Correction>> kCorrections{{"always", Correction::Always},
                                                                          {"on_split", Correction::OnSplit},
                                                                          {"end", Correction::End},
                                                                          {"off", Correction::Off}};
inline const std::vector<std::pair<std::string, UpdateScope>> kUpdateScopes{{"local", UpdateScope::Local},
                                                                            {"full", UpdateScope::Full}};
inline const std::vector<std::pair<std::string, PartitionSqem>> kPartitionSqems{
    {"diffused", PartitionSqem::Diffused}, {"vertex_normal", PartitionSqem::VertexNormal}};
inline const std::vector<std::pair<std::string, GaussNewtonSteps>> kGaussNewtonSteps{
    {"guarded", GaussNewtonSteps::Guarded}, {"raw", GaussNewtonSteps::Raw}};
inline const std::vector<std::pair<std::string, StopTest>> kStopTests{{"before_split", StopTest::BeforeSplit},
                                                                      {"after_split", StopTest::AfterSplit}};
inline const std::vector<std::pair<std::string, InitialSphere>> kInitialSpheres{
    {"largest_ball", InitialSphere::LargestBall}, {"box_corner", InitialSphere::BoxCorner}};

/// The vertex columns of VmasSolver::complex(): the cluster error E(C) (eq. 12, an area-weighted
/// mean of squared distances: length²), the cluster area A(C), and the stable sphere id.
inline const Property<double> kVmasError{Element::Vertex, "vmas_error", 2};
inline const Property<double> kVmasArea{Element::Vertex, "vmas_area", 2};
inline const Property<int> kVmasId{Element::Vertex, "vmas_id"};

struct VmasOptions {
  double lambda_partition = 0.2;  ///< λ in eq. 8 (partition and cluster errors)
  double lambda_update = 0.2;     ///< λ in eq. 11 (the update)
  PartitionSqem partition_sqem = PartitionSqem::Diffused;  ///< the SQEM term of eq. 8
  SqemRows sqem_rows = SqemRows::Paper;
  StopMode stop_mode = StopMode::Count;
  std::size_t target_spheres = 100;  ///< count mode
  double error_threshold = 2.5e-4;   ///< error mode, × scale²
  double converge_eps = 1e-5;        ///< |ΔE_tot| below this (× scale²) means converged
  int split_period = 10;             ///< a split round also every this many iterations
  double split_fraction = 0.2;       ///< at most ⌈fraction·|M|⌉ splits per round ...
  std::size_t split_max_per_round = 10;  ///< ... and at most this many
  std::size_t min_cluster_size = 4;  ///< spheres whose cluster is smaller are deleted
  int gn_max_iterations = 10;
  double gn_tolerance = 1e-6;        ///< × scale
  GaussNewtonSteps gn_steps = GaussNewtonSteps::Guarded;
  StopTest stop_test = StopTest::BeforeSplit;
  InitialSphere initial_sphere = InitialSphere::LargestBall;
  Correction correction = Correction::Always;
  UpdateScope update_scope = UpdateScope::Local;
  int max_iterations = 1000;
  /// Stop when for this many iterations the sphere count has not grown past its maximum and
  /// E_tot has not reached a new minimum (a target the tessellation cannot hold, or spheres
  /// oscillating between two positions, paper §5); 0 = never.
  int stall_iterations = 100;
};

using SphereId = std::uint64_t;

/// One sphere and its cluster, in the input's frame.
struct SphereInfo {
  SphereId id = 0;
  Vec3 centre = Vec3::Zero();
  double radius = 0;
  double error = 0;             ///< E(C) (eq. 12); 0 before the sphere's first partition
  double area = 0;              ///< A(C)
  std::size_t cluster_size = 0;
  Index split_vertex = 0;       ///< argmax_{v∈C} E_v
};

struct IterationReport {
  int iteration = 0;            ///< iterations completed so far (1-based)
  std::size_t spheres = 0;      ///< after the iteration, new splits included
  std::size_t culled = 0;       ///< spheres deleted for a too-small cluster
  std::size_t splits = 0;
  double energy_partition = 0;  ///< Σ_i Σ_{v∈C_i} E_v(m_i) after the partition
  double energy = 0;            ///< the same after the update (and correction)
  double total_error = 0;       ///< E_tot = Σ_i E(C_i)
  double max_error = 0;
  bool converged = false;       ///< |ΔE_tot| < converge_eps·scale²
  bool stalled = false;         ///< no progress for stall_iterations iterations
  bool stop = false;            ///< stop criterion met, stalled, or max_iterations reached
};

/// Wall time spent in each phase since the solver was made (seconds).
struct PhaseTimes {
  double partition = 0, update = 0, correction = 0, errors = 0, splits = 0, edits = 0;
  double total() const { return partition + update + correction + errors + splits + edits; }
};

class VmasSolver {
 public:
  /// Starts from one sphere, as `initial_sphere` says (notes §2.8).
  explicit VmasSolver(std::shared_ptr<const VmasInput> input, VmasOptions options = {});

  /// One iteration: partition (+ cull), update (+ correction), errors, and a split round when
  /// the schedule says so (converged, or every split_period iterations).
  IterationReport iterate();
  /// One iteration that never splits (after edits, to let the neighbourhood settle).
  IterationReport relax();
  /// Iterates until the stop criterion (or max_iterations). `after_each` sees every report and
  /// may edit the solver; returning false stops the run.
  IterationReport run(const std::function<bool(const IterationReport&)>& after_each = {});
  /// End of a run: the final correction (Correction::End, OnSplit) and the clusters of spheres
  /// that have none yet. Further iterations remain possible.
  void finish();

  // ---- dynamic edits: each repartitions and recomputes the errors; no restart -------------
  /// Adds a sphere: the shrinking ball at the cluster's max-error vertex. Returns its id.
  SphereId split_sphere(SphereId id);
  /// Deletes a sphere; its vertices go to the other spheres.
  void remove_sphere(SphereId id);
  /// Adds the shrinking ball of input vertex `vertex`. Returns its id.
  SphereId add_sphere(Index vertex);
  /// The sphere whose centre is nearest to p (input frame).
  SphereId nearest_sphere(const Vec3& p) const;
  bool contains(SphereId id) const;

  // ---- state ----------------------------------------------------------------------------------
  std::size_t size() const { return spheres_.size(); }
  std::vector<SphereInfo> spheres() const;
  SphereInfo sphere(SphereId id) const;
  /// Per input vertex: the index (into spheres()) of its cluster, or −1.
  const std::vector<int>& assignment() const { return cluster_of_; }
  /// Cluster adjacency (indices into spheres()).
  Adjacency adjacency() const;
  int iterations() const { return iteration_; }
  const IterationReport& last_report() const { return last_; }
  const VmasInput& input() const { return *input_; }
  const VmasOptions& options() const { return options_; }
  const PhaseTimes& times() const { return times_; }
  /// Spheres (centres in the input frame), generators = clusters (mesh vertices or samples),
  /// vertex columns kVmasError, kVmasArea, kVmasId; with `connect`, the dual's edges
  /// and triangles.
  MedialComplex complex(bool connect = false, TriangleRule rule = TriangleRule::Cliques) const;

 private:
  IterationReport step(bool allow_split);
  Sphere initial_sphere() const;
  std::size_t partition();  ///< assign + cull; returns the number culled
  void compute_stats();
  /// The Q_v of the partition and the cluster errors (partition_sqem).
  const std::vector<PackedQuadric>& partition_quadrics() const;
  void update_spheres();  ///< Gauss–Newton (+ correction) of the spheres due, by update_scope
  void correct_all();
  /// A split round (notes §2.9): new spheres at the max-error vertices of the clusters chosen by
  /// select_splits; returns how many were added.
  std::size_t split_round();
  /// Replaces sphere i, noting whether it moved (the next partition tests only moved spheres).
  void set_sphere(std::size_t i, const Sphere& s);
  void erase_sphere(std::size_t i);
  void refresh_after_edit();
  std::size_t index_of(SphereId id) const;
  SphereId push(const Sphere& s);

  std::shared_ptr<const VmasInput> input_;
  VmasOptions options_;
  std::vector<PackedQuadric> normal_quadrics_;  ///< PartitionSqem::VertexNormal only
  std::vector<Sphere> spheres_;  ///< local frame
  std::vector<SphereId> ids_;
  SphereId next_id_ = 0;
  // Per sphere, same order as spheres_:
  std::vector<char> moved_;      ///< changed (or added) since the last partition
  std::vector<char> regrouped_;  ///< its cluster gained or lost a vertex since its last update
  std::vector<char> settled_;    ///< its last update converged (local scope: no need to repeat it)
  std::vector<int> cluster_of_;  ///< exact argmin partition against the spheres not flagged in moved_
  Clusters clusters_;                 ///< for the first clusters_.count() spheres
  std::vector<ClusterStats> stats_;   ///< same
  int iteration_ = 0;
  double previous_total_ = std::numeric_limits<double>::infinity();
  double best_total_ = std::numeric_limits<double>::infinity();  ///< for the stall test
  std::size_t best_count_ = 0;
  int last_progress_ = 0;
  IterationReport last_;
  PhaseTimes times_;
};

/// The stop mode and thresholds as one line, for logs.
std::string summary(const VmasOptions& options);

}  // namespace medax::vmas
