#include "stages.hpp"

#include "edits.hpp"

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include <ostream>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace medax::vmas {

namespace {
constexpr const char* kDoc = "docs/plugins/vmas.md";

bool use_mesh(const Shape& shape, const std::string& input) {
  if (input == "mesh") return true;
  if (input == "samples") return false;
  return !shape.mesh.empty();
}
}  // namespace

// ---- vmas ------------------------------------------------------------------------------------

StageInfo VmasStage::describe() {
  using P = ParamSpec;
  return {"vmas",
          "Variational medial axis sampling (Huang et al. 2024): SQEM + Euclidean partition, "
          "Gauss-Newton spheres, shrinking-ball correction, coarse-to-fine splits, scripted edits",
          kDoc,
          {P::choice("input", "auto", {"auto", "mesh", "samples"},
                     "What to sample: the mesh's vertices, the oriented samples (point cloud), or the mesh "
                     "when there is one"),
           P::choice("stop_mode", "count", {"count", "error"},
                     "Stop at `target_spheres` spheres, or when every cluster error is below `error_threshold`"),
           P::integer("target_spheres", 100, "Sphere count of the count mode").at_least(1),
           P::real("error_threshold", 2.5e-4,
                   "Cluster error E(C) (eq. 12) below which a cluster is not split (error mode)")
               .at_least(0)
               .in_unit("scale²"),
           P::real("lambda_partition", 0.2, "λ of the partition and cluster errors (eq. 8)").at_least(0),
           P::real("lambda_update", 0.2, "λ of the sphere update (eq. 11)").at_least(0),
           P::choice("sqem_row_mode", "paper", {"paper", "author_code"},
                     "Update energy: the paper's sum of plane quadrics with Euclidean weight λ, or the "
                     "authors' code (one summed SQEM row per vertex, Euclidean weight λ²)"),
           P::choice("correction", "always", {"always", "on_split", "end", "off"},
                     "When spheres are projected back onto the medial axis by a shrinking ball"),
           P::choice("update_scope", "local", {"local", "full"},
                     "Spheres updated per iteration: those whose cluster changed (plus new and unconverged "
                     "ones; the others keep their exact values), or every sphere"),
           P::real("converge_eps", 1e-5, "Converged when the total error changes by less than this")
               .at_least(0)
               .in_unit("scale²"),
           P::integer("split_period", 10, "A split round also runs every this many iterations").at_least(1),
           P::real("split_fraction", 0.2, "At most ceil(fraction·|M|) splits per round").range(0, 1),
           P::integer("split_max_per_round", 10, "... and at most this many").at_least(1),
           P::integer("min_cluster_size", 4, "Spheres whose cluster has fewer vertices are deleted").at_least(1),
           P::integer("gn_max_iters", 10, "Gauss-Newton iterations per update").at_least(1),
           P::real("gn_tol", 1e-6, "Gauss-Newton stops when the step is shorter").at_least(0).in_unit("scale"),
           P::integer("knn_k", 6, "k of the kNN graph and diffused quadrics (point-cloud input)").at_least(1),
           P::real("sb_initial_radius", 1.0, "Initial shrinking-ball radius").at_least(0).in_unit("bbox diagonal"),
           P::integer("sb_max_iters", 30, "Shrinking-ball iterations").at_least(1),
           P::real("sb_angle_deg", 20.0, "Shrinking-ball denoising angle").range(0, 90).in_unit("degree"),
           P::integer("max_iterations", 1000, "Iteration cap").at_least(1),
           P::integer("stall_iterations", 100,
                      "Stop when neither the sphere count nor the total error has improved for this many "
                      "iterations (0: never)")
               .at_least(0),
           P::text("edits", "",
                   "Scripted edits, one per line or ';': `split|remove|add X Y Z [after K|end]` (split or "
                   "remove the sphere nearest to the point, add the shrinking ball of the nearest surface "
                   "vertex), after K iterations or at the end"),
           P::choice("edit_frame", "input", {"input", "working"},
                     "Frame of the edit points: the input file's coordinates, or the shape's current frame"),
           P::integer("relax_iterations", 10, "Iterations without splits after edits applied at the end")
               .at_least(0),
           P::boolean("trace", false,
                      "Write <id>_trace.csv to the run folder: per iteration the sphere count, splits, culls, "
                      "total and largest cluster error and the energy")}};
}

VmasOptions VmasStage::solver_options(const ParamSet& p) {
  VmasOptions o;
  o.lambda_partition = p.real("lambda_partition");
  o.lambda_update = p.real("lambda_update");
  o.sqem_rows = p.text("sqem_row_mode") == "paper" ? SqemRows::Paper : SqemRows::AuthorCode;
  o.stop_mode = p.text("stop_mode") == "count" ? StopMode::Count : StopMode::Error;
  o.target_spheres = static_cast<std::size_t>(p.integer("target_spheres"));
  o.error_threshold = p.real("error_threshold");
  o.converge_eps = p.real("converge_eps");
  o.split_period = static_cast<int>(p.integer("split_period"));
  o.split_fraction = p.real("split_fraction");
  o.split_max_per_round = static_cast<std::size_t>(p.integer("split_max_per_round"));
  o.min_cluster_size = static_cast<std::size_t>(p.integer("min_cluster_size"));
  o.gn_max_iterations = static_cast<int>(p.integer("gn_max_iters"));
  o.gn_tolerance = p.real("gn_tol");
  const std::string& c = p.text("correction");
  o.correction = c == "always" ? Correction::Always
                 : c == "on_split" ? Correction::OnSplit
                 : c == "end" ? Correction::End
                              : Correction::Off;
  o.update_scope = p.text("update_scope") == "local" ? UpdateScope::Local : UpdateScope::Full;
  o.max_iterations = static_cast<int>(p.integer("max_iterations"));
  o.stall_iterations = static_cast<int>(p.integer("stall_iterations"));
  return o;
}

InputOptions VmasStage::input_options(const ParamSet& p) {
  InputOptions o;
  o.knn = static_cast<std::size_t>(p.integer("knn_k"));
  o.sb_initial_radius = p.real("sb_initial_radius");
  o.sb_max_iterations = static_cast<int>(p.integer("sb_max_iters"));
  o.sb_angle_deg = p.real("sb_angle_deg");
  return o;
}

std::shared_ptr<const VmasInput> VmasStage::make_input(const Shape& shape, const std::string& input,
                                                       const InputOptions& options) {
  return use_mesh(shape, input) ? VmasInput::from_mesh(shape.mesh, options)
                                : VmasInput::from_samples(shape.samples, options);
}

void VmasStage::prepare(const Scene& scene) const {
  const std::string& input = params().text("input");
  const Shape& shape = scene.shape;
  if (use_mesh(shape, input)) {
    if (shape.mesh.empty()) throw std::invalid_argument("vmas: `input: mesh` but the shape has no mesh");
  } else {
    if (shape.samples.empty())
      throw std::invalid_argument("vmas: no oriented samples to sample from; add a `sample` conditioning stage "
                                  "before vmas or use `input: mesh`");
    if (shape.samples.normals.size() != shape.samples.size())
      throw std::invalid_argument("vmas: the samples have no normals; VMAS needs oriented samples");
  }
}

void VmasStage::check_params() const {
  parse_edits(params().text("edits"));  // a bad script is reported by `medax validate`
}

MedialComplex VmasStage::extract(const Shape& shape, Context& ctx) {
  const auto t0 = std::chrono::steady_clock::now();
  const VmasOptions options = solver_options(params());
  const auto input = make_input(shape, params().text("input"), input_options(params()));
  const auto t1 = std::chrono::steady_clock::now();
  ctx.info(fmt::format("vmas: {} {} ({} graph edges), scale {:.4g}; {}", input->size(),
                       input->kind == InputKind::Mesh ? "mesh vertices" : "samples", input->graph_edges.size(),
                       input->scale, summary(options)));
  VmasSolver solver(input, options);

  const std::vector<Edit> edits = parse_edits(params().text("edits"));
  const bool input_frame = params().text("edit_frame") == "input";
  const Similarity to_working = shape.to_input.inverse();
  std::size_t next = 0;
  int last_edit_at = -1;
  const auto apply_due = [&](int completed, bool all) {
    while (next < edits.size() && (all || (edits[next].after != Edit::kEnd && edits[next].after <= completed))) {
      const Edit& e = edits[next++];
      if (all && e.after != Edit::kEnd && e.after > completed)
        ctx.warn(fmt::format("vmas: the run stopped after {} iterations, before edit '{}'; applying it now",
                             completed, e.text));
      const Vec3 p = input_frame ? to_working.apply(e.point) : e.point;
      ctx.info("vmas: " + apply_edit(solver, e, p));
      last_edit_at = solver.iterations();
    }
  };
  apply_due(0, false);
  const bool count_mode = options.stop_mode == StopMode::Count;
  const double threshold = options.error_threshold * input->scale * input->scale;
  std::vector<IterationReport> trace;
  const bool tracing = params().boolean("trace");
  const IterationReport rep = solver.run([&](const IterationReport& r) {
    ctx.check_cancelled();
    if (tracing) trace.push_back(r);
    const double fraction = count_mode ? static_cast<double>(r.spheres) / static_cast<double>(options.target_spheres)
                                       : (r.max_error > 0 ? threshold / r.max_error : 1.0);
    ctx.progress(std::min(1.0, fraction), fmt::format("{} spheres", r.spheres));
    apply_due(r.iteration, false);
    return true;
  });
  const bool target_met = count_mode ? solver.size() >= options.target_spheres : rep.max_error < threshold;
  if (rep.stalled)
    ctx.warn(fmt::format("vmas: no progress for {} iterations, stopping with {} spheres{}", options.stall_iterations,
                         solver.size(),
                         target_met ? " (the spheres oscillate; see the paper's §5)"
                                    : " before the target: spheres added by splits keep losing their clusters (fewer "
                                      "than min_cluster_size vertices). The mesh is too coarse for this many spheres "
                                      "(the authors recommend |M| <= |V|/100): refine or resample it"));
  else if (!(rep.converged && target_met))
    ctx.warn(fmt::format("vmas: reached max_iterations ({}) before the stop criterion", options.max_iterations));
  apply_due(solver.iterations(), true);
  if (last_edit_at == solver.iterations())
    for (long long i = 0; i < params().integer("relax_iterations"); ++i) {
      ctx.check_cancelled();
      const IterationReport r = solver.relax();
      if (tracing) trace.push_back(r);
    }
  solver.finish();
  if (tracing) {
    const double s2 = input->scale * input->scale;
    ctx.write_output((id().empty() ? std::string("vmas") : id()) + "_trace.csv", [&](std::ostream& out) {
      out << "iteration,spheres,splits,culled,converged,total_error,max_error,energy_partition,energy,"
             "total_error_unit_box,max_error_unit_box\n";
      for (const IterationReport& r : trace)
        out << fmt::format("{},{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n", r.iteration, r.spheres,
                           r.splits, r.culled, r.converged ? 1 : 0, r.total_error, r.max_error, r.energy_partition,
                           r.energy, r.total_error / s2, r.max_error / s2);
    });
  }
  const auto t2 = std::chrono::steady_clock::now();
  const IterationReport& last = solver.last_report();
  const PhaseTimes& ph = solver.times();
  ctx.info(fmt::format("vmas: {} spheres after {} iterations; E_tot {:.4g}, max E(C) {:.4g} ({:.3g}·scale²); "
                       "{} threads: precompute {:.3f} s, optimisation {:.3f} s (partition {:.3f}, update {:.3f}, "
                       "correction {:.3f}, errors {:.3f}, splits {:.3f}, edits {:.3f})",
                       solver.size(), solver.iterations(), last.total_error, last.max_error,
                       last.max_error / (input->scale * input->scale), tbb::this_task_arena::max_concurrency(),
                       std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(),
                       ph.partition, ph.update, ph.correction, ph.errors, ph.splits, ph.edits));
  return solver.complex(false);
}

// ---- vmas_dual -------------------------------------------------------------------------------

StageInfo VmasDualStage::describe() {
  using P = ParamSpec;
  return {"vmas_dual",
          "VMAS connectivity: an edge where two clusters touch, a triangle per three mutually adjacent "
          "clusters (the dual of the partition)",
          kDoc,
          {P::choice("triangles", "cliques", {"cliques", "restricted", "none"},
                     "Triangles: every 3-clique (the paper), only cliques realised by a surface triangle "
                     "spanning three clusters (meshes), or none"),
           P::choice("input", "auto", {"auto", "mesh", "samples"},
                     "Surface the clusters live on when the complex carries none (auto: the mesh if any)"),
           P::real("lambda_partition", 0.2,
                   "λ of eq. 8 when the complex carries no clusters and they are recomputed from the spheres")
               .at_least(0),
           P::integer("knn_k", 6, "k of the kNN graph for point-cloud clusters (as in vmas)").at_least(1)}};
}

void VmasDualStage::prepare(const Scene& scene) const {
  ConnectivityStage::prepare(scene);
  if (scene.shape.mesh.empty() && scene.shape.samples.empty())
    throw std::invalid_argument("vmas_dual: the shape has neither a mesh nor samples to take adjacency from");
  if (params().text("triangles") == "restricted" && scene.shape.mesh.empty())
    throw std::invalid_argument("vmas_dual: `triangles: restricted` needs a mesh; use `cliques` for point clouds");
}

void VmasDualStage::connect(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const std::size_t count = medial.num_vertices();
  const std::string& rule_text = params().text("triangles");
  const TriangleRule rule = rule_text == "cliques"      ? TriangleRule::Cliques
                            : rule_text == "restricted" ? TriangleRule::Restricted
                                                        : TriangleRule::None;
  const std::size_t k = static_cast<std::size_t>(params().integer("knn_k"));
  // The clusters: the extraction's generators when they are VMAS clusters of this shape ...
  bool on_mesh = use_mesh(shape, params().text("input"));
  if (medial.generator_kind == "mesh_vertex") on_mesh = true;
  if (medial.generator_kind == "sample") on_mesh = false;
  if (on_mesh && shape.mesh.empty()) throw std::invalid_argument("vmas_dual: the clusters are on a mesh but the shape has none");
  if (!on_mesh && shape.samples.empty())
    throw std::invalid_argument("vmas_dual: the clusters are on samples but the shape has none");
  const std::size_t n = on_mesh ? shape.mesh.vertices.size() : shape.samples.size();
  std::vector<int> cluster_of(n, -1);
  bool have = medial.generators.size() == count && count > 0 &&
              (medial.generator_kind == "mesh_vertex" || medial.generator_kind == "sample");
  if (have) {
    for (std::size_t i = 0; i < count && have; ++i)
      for (Index v : medial.generators[i]) {
        if (v >= n) {
          have = false;
          break;
        }
        if (cluster_of[v] < 0) cluster_of[v] = static_cast<int>(i);
      }
    if (!have) ctx.warn("vmas_dual: the generators do not index this shape; recomputing the clusters");
  }
  std::vector<Segment> graph;
  if (!have) {
    // ... or the partition of eq. 8 recomputed from the spheres (e.g. another extractor's).
    std::fill(cluster_of.begin(), cluster_of.end(), -1);
    InputOptions io;
    io.knn = k;
    io.shrinking_balls = false;
    const auto in = on_mesh ? VmasInput::from_mesh(shape.mesh, io) : VmasInput::from_samples(shape.samples, io);
    std::vector<Sphere> spheres(count);
    for (std::size_t i = 0; i < count; ++i) spheres[i] = {medial.centres[i] - in->origin, medial.radii[i]};
    assign_vertices(*in, spheres, params().real("lambda_partition"), cluster_of);
    medial.generators.assign(count, {});
    for (Index v = 0; v < n; ++v)
      if (cluster_of[v] >= 0) medial.generators[static_cast<std::size_t>(cluster_of[v])].push_back(v);
    medial.generator_kind = on_mesh ? "mesh_vertex" : "sample";
    graph = in->graph_edges;
    ctx.info("vmas_dual: clusters recomputed from the spheres (eq. 8)");
  } else {
    graph = on_mesh ? mesh_edges(shape.mesh.faces) : knn_edges(shape.samples.points, k);
  }
  const DualComplex d = dual_complex(cluster_adjacency(graph, cluster_of, count), rule,
                                     on_mesh ? shape.mesh.faces : std::vector<Tri>{}, cluster_of);
  medial.edges = d.edges;
  medial.faces = d.faces;
  medial.edge_props = {};
  medial.face_props = {};
  ctx.info(fmt::format("vmas_dual: {} spheres, {} edges, {} triangles ({})", count, d.edges.size(), d.faces.size(),
                       rule_text));
}

}  // namespace medax::vmas
