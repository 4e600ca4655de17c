#include "stages.hpp"

#include "edits.hpp"

#include <medax/services/mesh_check.hpp>

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <ostream>
#include <stdexcept>

namespace medax::vmas {

namespace {
constexpr const char* kDoc = "docs/plugins/vmas.md";

bool use_mesh(const Shape& shape, Surface surface) {
  if (surface == Surface::Mesh) return true;
  if (surface == Surface::Samples) return false;
  return !shape.mesh.empty();
}

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

/// The likely cause when no shrinking ball shrank: every ball grows along the normal, so normals
/// pointing out of the solid find no second contact. Only computed once the solver has failed.
std::string no_ball_hint(const Shape& shape, bool on_mesh) {
  if (on_mesh) {
    const services::MeshReport r = services::check_mesh(shape.mesh, {/*self_intersections=*/false});
    if (r.closed && r.consistently_oriented && r.relative_volume < 0)
      return "the mesh's faces point inward (its signed volume is negative), so every ball grows out of the "
             "solid. Put `- plugin: repair` before vmas (it flips the faces outward), or reorient the faces in the "
             "file";
    if (!r.valid_solid())
      return "the mesh does not bound a solid (" + r.summary() + "). Put `- plugin: repair` before vmas: it fixes "
             "the orientation and names what it cannot fix";
    return "the mesh is a valid solid; try a larger sb_initial_radius";
  }
  return "check that the sample normals point out of the solid (a `sample` stage after `repair` takes them from "
         "outward faces; for a point cloud, a `normals` stage with `orient: true` orients them)";
}

/// The solver, with the likely cause added when it cannot start.
VmasSolver start_solver(std::shared_ptr<const VmasInput> input, const VmasOptions& options, const Shape& shape) {
  const bool on_mesh = input->kind == InputKind::Mesh;
  try {
    return VmasSolver(std::move(input), options);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + ": " + no_ball_hint(shape, on_mesh));
  }
}

/// The scripted edits not applied yet, in order, and when the last one was applied.
class EditSchedule {
 public:
  /// `to_working` maps the script's points to the shape's frame (none: they are in it already).
  EditSchedule(std::vector<Edit> edits, std::optional<Similarity> to_working)
      : edits_(std::move(edits)), to_working_(std::move(to_working)) {}

  /// Applies, and logs, the edits due once `completed` iterations are done (every one left when
  /// `all`, with a warning for those whose iteration the run never reached).
  void apply_due(VmasSolver& solver, int completed, bool all, Context& ctx) {
    while (next_ < edits_.size() &&
           (all || (edits_[next_].after != Edit::kEnd && edits_[next_].after <= completed))) {
      const Edit& e = edits_[next_++];
      if (all && e.after != Edit::kEnd && e.after > completed)
        ctx.warn(fmt::format("the run stopped after {} iterations, before edit '{}'; applying it now", completed,
                             e.text));
      const Vec3 p = to_working_ ? to_working_->apply(e.point) : e.point;
      ctx.info(apply_edit(solver, e, p));
      last_applied_ = solver.iterations();
    }
  }
  /// The solver's iteration count when the last edit was applied (−1: none yet).
  int last_applied() const { return last_applied_; }

 private:
  std::vector<Edit> edits_;
  std::optional<Similarity> to_working_;
  std::size_t next_ = 0;
  int last_applied_ = -1;
};

/// The stop criterion's target: the sphere count (count mode) or every cluster error below the
/// threshold (error mode, `threshold` absolute).
bool target_met(const VmasSolver& solver, const IterationReport& rep, double threshold) {
  return solver.options().stop_mode == StopMode::Count ? solver.size() >= solver.options().target_spheres
                                                       : rep.max_error < threshold;
}

/// Says why the run stopped when it did not stop at its criterion.
void warn_if_stopped_early(const VmasSolver& solver, const IterationReport& rep, double threshold, Context& ctx) {
  const VmasOptions& options = solver.options();
  const bool met = target_met(solver, rep, threshold);
  if (rep.stalled)
    ctx.warn(fmt::format("no progress for {} iterations, stopping with {} spheres{}", options.stall_iterations,
                         solver.size(),
                         met ? " (the spheres oscillate; see the paper's §5)"
                             : " before the target: spheres added by splits keep losing their clusters (fewer than "
                               "min_cluster_size vertices). The mesh is too coarse for this many spheres (the authors "
                               "recommend |M| <= |V|/100): refine or resample it"));
  else if (!(rep.converged && met))
    ctx.warn(fmt::format("reached max_iterations ({}) before the stop criterion", options.max_iterations));
}

/// `<id>_trace.csv`: one row per iteration.
void write_trace(const std::vector<IterationReport>& trace, double scale, Context& ctx) {
  const double s2 = scale * scale;
  ctx.write_output(ctx.stage_id() + "_trace.csv", [&](std::ostream& out) {
    out << "iteration,spheres,splits,culled,converged,total_error,max_error,energy_partition,energy,"
           "total_error_unit_box,max_error_unit_box\n";
    for (const IterationReport& r : trace)
      out << fmt::format("{},{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n", r.iteration, r.spheres,
                         r.splits, r.culled, r.converged ? 1 : 0, r.total_error, r.max_error, r.energy_partition,
                         r.energy, r.total_error / s2, r.max_error / s2);
  });
}
}  // namespace

// ---- vmas ------------------------------------------------------------------------------------

StageInfo VmasStage::describe() {
  return {"vmas",
          "Variational medial axis sampling (Huang et al. 2024): SQEM + Euclidean partition, "
          "Gauss-Newton spheres, shrinking-ball correction, coarse-to-fine splits, scripted edits",
          kDoc};
}

void VmasStage::declare(ParamBinder& p) {
  VmasOptions& o = options_;
  InputOptions& in = input_options_;
  p.add("input", input_, kSurfaces,
        "What to sample: the mesh's vertices, the oriented samples (point cloud), or the mesh when there is one");
  p.add("stop_mode", o.stop_mode, kStopModes,
        "Stop at `target_spheres` spheres, or when every cluster error is below `error_threshold`");
  p.add("target_spheres", o.target_spheres,
        "Sphere count of the count mode (the CGAL port's default; the paper uses Table 1's counts)")
      .at_least(1);
  p.add("error_threshold", o.error_threshold,
        "Cluster error E(C) (eq. 12) below which a cluster is not split (error mode; the authors' default)")
      .at_least(0)
      .in_unit("scale²");
  p.add("lambda_partition", o.lambda_partition, "λ of the partition and cluster errors (eq. 8)").at_least(0);
  p.add("lambda_update", o.lambda_update, "λ of the sphere update (eq. 11)").at_least(0);
  p.add("partition_sqem", o.partition_sqem, kPartitionSqems,
        "SQEM term of the partition and cluster errors: the diffused quadric of eq. 7 (the paper), or one plane "
        "through the vertex with its normal, weighted by A(v) (the CGAL port)");
  p.add("sqem_row_mode", o.sqem_rows, kSqemRows,
        "Update energy: the paper's sum of plane quadrics with Euclidean weight λ, or the authors' code (one "
        "summed SQEM row per vertex, Euclidean weight λ²)");
  p.add("correction", o.correction, kCorrections,
        "When spheres are projected back onto the medial axis by a shrinking ball");
  p.add("update_scope", o.update_scope, kUpdateScopes,
        "Spheres updated per iteration: those whose cluster changed since their last update, new ones and those "
        "whose last Gauss-Newton solve hit `gn_max_iters` (the others keep their exact values); or every sphere");
  p.add("converge_eps", o.converge_eps, "Converged when the total error changes by less than this")
      .at_least(0)
      .in_unit("scale²");
  p.add("split_period", o.split_period, "A split round also runs every this many iterations").at_least(1);
  p.add("split_fraction", o.split_fraction, "At most ceil(fraction·|M|) splits per round").range(0, 1);
  p.add("split_max_per_round", o.split_max_per_round, "... and at most this many").at_least(1);
  p.add("min_cluster_size", o.min_cluster_size, "Spheres whose cluster has fewer vertices are deleted").at_least(1);
  p.add("gn_max_iters", o.gn_max_iterations, "Gauss-Newton iterations per update").at_least(1);
  p.add("gn_tol", o.gn_tolerance, "Gauss-Newton stops when the step is shorter").at_least(0).in_unit("scale");
  p.add("gn_steps", o.gn_steps, kGaussNewtonSteps,
        "Gauss-Newton steps: guarded (a step that raises the energy or makes r <= 0 is damped and retried), or "
        "raw (every step taken, as the authors' code)");
  p.add("stop_test", o.stop_test, kStopTests,
        "When the count mode stops: converged at the target before a split round (the paper), or also right after "
        "a split round on convergence that reaches it, its new spheres unoptimised (the CGoGN code)");
  p.add("initial_sphere", o.initial_sphere, kInitialSpheres,
        "First sphere: the largest per-vertex shrinking ball (the CGoGN code), or the bbox min corner with radius "
        "= scale (the CGAL port's ((0,0,0), 1))");
  p.add("knn_k", in.knn, "k of the kNN graph and diffused quadrics (point-cloud input)").at_least(1);
  p.add("sb_initial_radius", in.sb_initial_radius, "Initial shrinking-ball radius r0")
      .at_least(0)
      .in_unit("bbox diagonal");
  p.add("sb_max_iters", in.sb_max_iterations, "Shrinking-ball iterations").at_least(1);
  p.add("sb_angle_deg", in.sb_angle_deg, "Shrinking-ball denoising angle").range(0, 90).in_unit("degree");
  p.add("sb_contacts", in.sb_contacts, kBallContacts,
        "Second contact of a shrinking ball (split seeds and correction): the nearest vertex (the CGoGN code), or "
        "the closest point on the faces (the CGAL port; meshes only)");
  p.add("sb_min_radius", in.sb_min_radius,
        "sb_contacts: faces: a ball stops before shrinking below this radius (the CGAL port's 0.01)")
      .at_least(0)
      .in_unit("scale");
  p.add("max_iterations", o.max_iterations, "Iteration cap (warns when reached)").at_least(1);
  p.add("stall_iterations", o.stall_iterations,
        "Stop, with a warning that says why, when neither the sphere count nor the total error has improved for "
        "this many iterations (0: never; not in the paper)")
      .at_least(0);
  p.add("edits", edits_,
        "Scripted edits, one per line or ';': `split|remove|add X Y Z [after K|end]` (split or remove the sphere "
        "nearest to the point, add the shrinking ball of the nearest surface vertex), after K iterations or at "
        "the end");
  p.add("edit_frame", edit_frame_, {{"input", EditFrame::Input}, {"working", EditFrame::Working}},
        "Frame of the edit points: the input file's coordinates, or the shape's current frame");
  p.add("relax_iterations", relax_iterations_, "Iterations without splits after edits applied at the end")
      .at_least(0);
  p.add("trace", trace_,
        "Write `<id>_trace.csv` to the run folder: per iteration the sphere count, splits, culls, total and largest "
        "cluster error and the energy");
}

std::shared_ptr<const VmasInput> VmasStage::make_input(const Shape& shape, Surface surface,
                                                       const InputOptions& options) {
  return use_mesh(shape, surface) ? VmasInput::from_mesh(shape.mesh, options)
                                  : VmasInput::from_samples(shape.samples, options);
}

std::vector<ShapePart> VmasStage::needs() const {
  if (input_ == Surface::Samples) return {ShapePart::Samples};
  return {};
}

void VmasStage::check_scene(const Scene& scene) const {
  const Shape& shape = scene.shape;
  if (use_mesh(shape, input_)) {
    if (shape.mesh.empty())
      throw std::invalid_argument("`input: mesh` but the shape has no mesh: for a point cloud use `input: samples` "
                                  "(or auto), or put `reconstruct_mesh` before it");
  } else {
    if (shape.samples.empty())
      throw std::invalid_argument("no oriented samples to sample from; add a `sample` conditioning stage before "
                                  "vmas or use `input: mesh`");
    if (shape.samples.normals.size() != shape.samples.size())
      throw std::invalid_argument("the samples have no normals; VMAS needs oriented samples: put a `normals` stage "
                                  "before it");
    if (shape.samples.size() < input_options_.knn + 1)
      throw std::invalid_argument(fmt::format("{} samples are too few for the kNN graph with knn_k = {}: give a "
                                              "denser cloud or lower knn_k",
                                              shape.samples.size(), input_options_.knn));
  }
}

void VmasStage::check_params() const {
  parse_edits(edits_);  // a bad script is reported by `medax validate`
}

MedialComplex VmasStage::extract(const Shape& shape, Context& ctx) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto input = make_input(shape, input_, input_options_);
  const auto t1 = Clock::now();
  ctx.info(fmt::format("{} {} ({} graph edges), scale {:.4g}; {}", input->size(),
                       input->kind == InputKind::Mesh ? "mesh vertices" : "samples", input->graph_edges.size(),
                       input->scale, summary(options_)));
  VmasSolver solver = start_solver(input, options_, shape);
  EditSchedule edits(parse_edits(edits_), edit_frame_ == EditFrame::Input
                                              ? std::optional<Similarity>(shape.to_input.inverse())
                                              : std::nullopt);
  edits.apply_due(solver, 0, false, ctx);

  // The optimisation, with the edits due on the way.
  const double threshold = options_.error_threshold * input->scale * input->scale;
  std::vector<IterationReport> trace;
  const IterationReport rep = solver.run([&](const IterationReport& r) {
    ctx.check_cancelled();
    if (trace_) trace.push_back(r);
    const double fraction = options_.stop_mode == StopMode::Count
                                ? static_cast<double>(r.spheres) / static_cast<double>(options_.target_spheres)
                                : (r.max_error > 0 ? threshold / r.max_error : 1.0);
    ctx.progress(std::min(1.0, fraction), fmt::format("{} spheres", r.spheres));
    edits.apply_due(solver, r.iteration, false, ctx);
    return true;
  });
  warn_if_stopped_early(solver, rep, threshold, ctx);

  // The edits left, then iterations without splits to let them settle.
  edits.apply_due(solver, solver.iterations(), true, ctx);
  if (edits.last_applied() == solver.iterations())
    for (int i = 0; i < relax_iterations_; ++i) {
      ctx.check_cancelled();
      const IterationReport r = solver.relax();
      if (trace_) trace.push_back(r);
    }
  solver.finish();
  if (trace_) write_trace(trace, input->scale, ctx);

  const auto t2 = Clock::now();
  const IterationReport& last = solver.last_report();
  const PhaseTimes& ph = solver.times();
  ctx.info(fmt::format("{} spheres after {} iterations; E_tot {:.4g}, max E(C) {:.4g} ({:.3g}·scale²); {} threads: "
                       "precompute {:.3f} s, optimisation {:.3f} s (partition {:.3f}, update {:.3f}, correction "
                       "{:.3f}, errors {:.3f}, splits {:.3f}, edits {:.3f})",
                       solver.size(), solver.iterations(), last.total_error, last.max_error,
                       last.max_error / (input->scale * input->scale), tbb::this_task_arena::max_concurrency(),
                       seconds(t1 - t0), seconds(t2 - t1), ph.partition, ph.update, ph.correction, ph.errors,
                       ph.splits, ph.edits));
  return solver.complex(false);
}

// ---- vmas_dual -------------------------------------------------------------------------------

StageInfo VmasDualStage::describe() {
  return {"vmas_dual",
          "VMAS connectivity: an edge where two clusters touch, a triangle per three mutually adjacent "
          "clusters (the dual of the partition)",
          kDoc};
}

void VmasDualStage::declare(ParamBinder& p) {
  p.add("triangles", triangles_, kTriangleRules,
        "Triangles: every 3-clique (the paper), only cliques realised by a surface triangle spanning three "
        "clusters (meshes), or none");
  p.add("input", input_, kSurfaces,
        "Surface the clusters live on when the complex carries none (auto: the mesh if any)");
  p.add("lambda_partition", lambda_partition_,
        "λ of eq. 8 when the complex carries no clusters and they are recomputed from the spheres")
      .at_least(0);
  p.add("knn_k", input_options_.knn, "k of the kNN graph for point-cloud clusters (as in vmas)").at_least(1);
}

void VmasDualStage::check_scene(const Scene& scene) const {
  if (scene.shape.mesh.empty() && scene.shape.samples.empty())
    throw std::invalid_argument("the shape has neither a mesh nor samples to take adjacency from");
  if (triangles_ == TriangleRule::Restricted && scene.shape.mesh.empty())
    throw std::invalid_argument("`triangles: restricted` needs a mesh; use `cliques` for point clouds");
}

namespace {
/// cluster_of (over the n surface points) from the complex's generators, each point in the first
/// cluster that lists it; nothing when a generator is not one of the n points.
std::optional<std::vector<int>> clusters_from_generators(const MedialComplex& medial, std::size_t n) {
  std::vector<int> cluster_of(n, -1);
  for (std::size_t i = 0; i < medial.num_vertices(); ++i)
    for (Index v : medial.generators[i]) {
      if (v >= n) return std::nullopt;
      if (cluster_of[v] < 0) cluster_of[v] = static_cast<int>(i);
    }
  return cluster_of;
}
}  // namespace

std::vector<Segment> VmasDualStage::recompute_clusters(const Shape& shape, bool on_mesh, MedialComplex& medial,
                                                       std::vector<int>& cluster_of) const {
  const std::size_t count = medial.num_vertices();
  const auto in = on_mesh ? VmasInput::from_mesh(shape.mesh, input_options_)
                          : VmasInput::from_samples(shape.samples, input_options_);
  std::vector<Sphere> spheres(count);
  for (std::size_t i = 0; i < count; ++i) spheres[i] = {medial.centres[i] - in->origin, medial.radii[i]};
  assign_vertices(*in, spheres, lambda_partition_, cluster_of);
  medial.generators.assign(count, {});
  for (Index v = 0; v < cluster_of.size(); ++v)
    if (cluster_of[v] >= 0) medial.generators[static_cast<std::size_t>(cluster_of[v])].push_back(v);
  medial.generator_kind = on_mesh ? "mesh_vertex" : "sample";
  return in->graph_edges;
}

void VmasDualStage::connect(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const std::size_t count = medial.num_vertices();
  // The surface of the clusters: the generators' when they say, else as `input` says.
  bool on_mesh = use_mesh(shape, input_);
  if (medial.generator_kind == "mesh_vertex") on_mesh = true;
  if (medial.generator_kind == "sample") on_mesh = false;
  if (on_mesh && shape.mesh.empty()) throw std::invalid_argument("the clusters are on a mesh but the shape has none");
  if (!on_mesh && shape.samples.empty())
    throw std::invalid_argument("the clusters are on samples but the shape has none");
  const std::size_t n = on_mesh ? shape.mesh.vertices.size() : shape.samples.size();

  // The clusters: the extraction's generators when they are VMAS clusters of this shape, or the
  // partition of eq. 8 recomputed from the spheres (e.g. another extractor's).
  const bool listed = medial.generators.size() == count && count > 0 &&
                      (medial.generator_kind == "mesh_vertex" || medial.generator_kind == "sample");
  std::optional<std::vector<int>> given = listed ? clusters_from_generators(medial, n) : std::nullopt;
  if (listed && !given) ctx.warn("the generators do not index this shape; recomputing the clusters");
  std::vector<int> cluster_of;
  std::vector<Segment> graph;
  if (given) {
    cluster_of = std::move(*given);
    graph = on_mesh ? mesh_edges(shape.mesh.faces) : knn_edges(shape.samples.points, input_options_.knn);
  } else {
    graph = recompute_clusters(shape, on_mesh, medial, cluster_of);
    ctx.info("clusters recomputed from the spheres (eq. 8)");
  }

  const DualComplex d = dual_complex(cluster_adjacency(graph, cluster_of, count), triangles_,
                                     on_mesh ? shape.mesh.faces : std::vector<Tri>{}, cluster_of);
  medial.edges = d.edges;
  medial.faces = d.faces;
  medial.edge_props = {};
  medial.face_props = {};
  ctx.info(fmt::format("{} spheres, {} edges, {} triangles ({})", count, d.edges.size(), d.faces.size(),
                       choice_name(kTriangleRules, triangles_)));
}

}  // namespace medax::vmas
