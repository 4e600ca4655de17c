#include "stages.hpp"

#include "medial_json.hpp"
#include "output.hpp"

#include <medax/representation_size.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <stdexcept>

namespace medax::msd {
namespace {

using Clock = MsdStage::Clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}
/// Process CPU time (all threads) since `start`.
double cpu_seconds_since(std::clock_t start) { return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC; }

const char* kRadiusRule = "vertex radius = mean ρ of the vertex primitive (ρ0 when its fit failed)";
const char* kCountRule = "MSD (Guo et al. 2024 §6): N_d = #v + #e + #f, N_c = Σ|V(T_P)| + 3·#v over the final (refined or fitted) primitives";

std::string iteration_line(const IterationLog& it) {
  const Energy& e = it.energy;
  const std::string energy =
      e.rejected ? fmt::format("rejected ({})", e.rejection)
                 : fmt::format("E {:.5f} (cov {:.5f}, cent {:.5f}, count {:.0f})", e.total, e.coverage, e.centroid,
                               e.count);
  return fmt::format("iteration {} round {}: {} sites, {}, best {:.5f}; {} fitted; projection {:.3f} s, "
                     "construction {:.3f} s, fitting {:.3f} s, energy {:.3f} s",
                     it.iteration, it.round, it.sites, energy, it.best, it.fitted, it.seconds_projection,
                     it.seconds_construction, it.seconds_fitting, it.seconds_energy);
}

}  // namespace

StageInfo MsdStage::describe() {
  return {"msd",
          "Medial Skeletal Diagram (Guo et al. 2024): a sparse skeleton on the medial mesh with a fitted "
          "enveloping primitive per vertex, edge and triangle, sites placed by Nelder-Mead on coverage",
          "docs/plugins/msd.md"};
}

void MsdStage::declare(ParamBinder& p) {
  declare_optimisation(p);
  declare_fitting(p);
  declare_construction(p);
  declare_outputs(p);
}

void MsdStage::declare_optimisation(ParamBinder& p) {
  OptimisationOptions& o = options_;
  p.add("n_init", o.initial_sites, "initial sites |V⁽⁰⁾|, farthest points on M's graph distances (paper: 10)")
      .range(1, 1e6);
  p.add("start_vertex", o.start_vertex, "M vertex the farthest-point selection starts at (authors' code: 0)");
  p.add("c1", o.centroid_weight, "weight of E_cent (paper: 1)").range(0, 1e9);
  p.add("c2", o.count_weight, "weight of E_count = |V̂| − |V| (paper: 1e-3)").range(0, 1e9);
  p.add("projection", o.projection,
        {{"closest_point", Projection::ClosestPoint}, {"facet_centroid", Projection::FacetCentroid}},
        "trial point → site: closest point of M (paper) or centroid of M's closest facet (authors' code; two "
        "sites on one facet reject the trial)");
  p.add("min_site_distance", o.min_site_distance, "trials with two sites closer than this are rejected (E = 1e3)")
      .range(0, 1).in_unit("unit box");
  p.add("first_iterations", o.first_iterations, "energy evaluations of the first round (paper: 50)").range(1, 1e6);
  p.add("add_every", o.add_every, "energy evaluations of every later round (paper: 30)").range(1, 1e6);
  p.add("add_count", o.add_count, "sites added per round at the largest uncovered regions (paper: 3 or 5)")
      .range(0, 1e6);
  p.add("stall", o.stall, "a round ends after this many evaluations without decrease (paper: 5)").range(1, 1e6);
  p.add("max_iterations", o.max_iterations, "energy evaluations in all (the paper gives no value)").range(1, 1e7);
  p.add("xtol", o.xtol, "Nelder-Mead xtol_abs (authors' code: 1e-2)").range(0, 1).in_unit("unit box");
  p.add("tetgen_switches", o.tetgen_switches, "TetGen switches for the uncovered-volume tets (authors' code: pq1.05)");
  p.add("delta_rule", o.delta_rule, {{"mean_edge_length", DeltaRule::MeanEdgeLength}, {"value", DeltaRule::Value}},
        "δ of E_cov: ℓ̄, the mean edge length of S (authors' code), or `delta` (paper: 1e-4, below the chord "
        "error of T_P, so S's vertices are rarely covered)");
  p.add("delta", o.coverage.delta, "δ when delta_rule is `value`: a vertex of S is covered when ℰ(v; T_P) < δ")
      .range(0, 1).in_unit("unit box");
  p.add("coverage_test", o.coverage.test,
        {{"radial", CoverageTest::Radial}, {"signed_distance", CoverageTest::SignedDistance}},
        "ℰ by the radial test of Eq. 3 or the signed distance to T_P");
}

void MsdStage::declare_fitting(ParamBinder& p) {
  FitOptions& f = options_.fit;
  p.add("smoothness", f.smoothness, "λ, weight of E_smooth = ρᵀLρ (paper: 1; authors' code 0.1, and 0 while "
                                    "optimising)").range(0, 1e9);
  p.add("w", f.expansion, "w, weight of E_exp (paper: 10; authors' code 2)").range(0, 1e12);
  p.add("w_hat", f.contact, "ŵ, penalty weight on ρ_i > ρmax_i (paper: 1e4)").range(0, 1e15);
  p.add("progressions", f.progressions, "times the target radius is raised (paper: 25)").range(1, 1e4);
  p.add("step", f.step_fraction, "raise per progression as a fraction of ρ0 (paper: 0.1)").range(0, 10);
  p.add("inner", f.max_iterations, "penalty iterations per progression at most (paper: 15)").range(1, 1e4);
  p.add("search_smoothness", options_.search_smoothness, "λ while optimising (authors' code: 0); the final fit "
                                                          "uses `smoothness`").range(0, 1e9);
  p.add("search_sphere_vertices", options_.search_sphere_vertices, "template size while optimising; the final fit "
                                                                   "uses `sphere_vertices`").range(12, 1e6);
  p.add("neighbour_cap", f.neighbour_cap, "authors' code: a direction's raise shrinks as it outgrows its smallest "
                                          "neighbour (off in the paper)");
  p.add("sphere_vertices", f.templates.sphere_vertices, "vertices of the vertex template; sets the angular step of "
                                                        "every template (paper: 1,588)").range(12, 1e6);
  p.add("max_segments", f.templates.max_segments, "cap on template segments along an edge or triangle side")
      .range(1, 1e5);
}

void MsdStage::declare_construction(ParamBinder& p) {
  ConstructionOptions& c = options_.construction;
  p.add("multi_interface", c.multi_interface, "S3 d: a polyline per extra interface between two cells");
  p.add("max_bisection_depth", c.max_bisection_depth, "S3 e: an edge crossing S is split into at most 2^depth parts")
      .range(0, 30);
  p.add("collapse_angle", c.collapse_angle_deg, "S3 g: degree-2 vertices straighter than this are removed")
      .range(0, 180).in_unit("deg");
}

void MsdStage::declare_outputs(ParamBinder& p) {
  p.add("refine", refine_, "S7: refine every fitted primitive so that it reproduces the part of S it covers with S's "
                           "own vertices and triangles (paper §5.4); off gives the fitting-only MSD");
  p.add("select_distance", refine_options_.select_distance,
        "refinement: a vertex of S is selected when its distance to T_P is below this (authors' code: 1e-3)")
      .range(0, 1).in_unit("unit box");
  p.add("select_reach", refine_options_.select_reach,
        "refinement: ... or when the segment from the element to it does not cross S and meets T_P within this "
        "many mean edge lengths ℓ̄ of it (authors' code: 2)").range(0, 1e3);
  p.add("cleanup_length", refine_options_.cleanup_length,
        "refinement clean-up: template vertices within this of the S triangles a primitive takes over are "
        "removed, so no slivers remain (authors' code: 5e-3)").range(0, 1).in_unit("unit box");
  p.add("reconstruction", reconstruction_,
        {{"union", ReconstructionMode::Union}, {"sdf", ReconstructionMode::Sdf}, {"none", ReconstructionMode::None}},
        "Ŝ = ∪ T_P, published for the evaluation stages and written as <id>_reconstruction.off: `union` keeps the "
        "primitives' triangles outside the others (no grid; for the error figures), `sdf` meshes a signed-distance "
        "grid by OpenVDB (the paper's timed SDF reconstruction), `none` builds nothing");
  p.add("union_tolerance", union_.tolerance,
        "union: a point is inside another primitive only deeper than this; nearer its surface it is on it and "
        "kept (shared faces, and surfaces interleaving within the fitted T_P's chord error)")
      .range(0, 1e-2).in_unit("unit box");
  p.add("reconstruction_resolution", sdf_.resolution,
        "sdf: voxels of Ŝ's grid across the longest side of the primitives' bounding box (paper: 256)")
      .range(8, 4096);
  p.add("write_primitives", write_primitives_, "write every final primitive into <id>_primitives.ply");
}

void MsdStage::check_scene(const Scene& scene) const {
  if (scene.shape.mesh.faces.size() < 4)
    throw std::invalid_argument("the shape has no closed surface mesh; MSD fits primitives against S "
                                "(`reconstruct_mesh` makes one of a point cloud)");
  if (scene.medial && scene.medial->num_vertices() == 0)
    throw std::invalid_argument("the medial mesh M is empty; give an extraction stage (e.g. vmas + vmas_dual) "
                                "or msd_medial with the authors' JSON");
}

void MsdStage::simplify(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const auto start = Clock::now();
  TargetMesh target(shape.mesh);
  MedialMesh mesh = MedialMesh::from_complex(medial, 1e-9 * target.scale());
  ctx.info(fmt::format("S: {} vertices, {} triangles, ℓ̄ {:.4g}; M: {} vertices, {} triangles, {} dangling edges",
                       shape.mesh.vertices.size(), shape.mesh.faces.size(), target.mean_edge_length(),
                       mesh.points().size(), mesh.triangles().size(), mesh.dangling_edges().size()));
  const auto on_iteration = [&](const IterationLog& it) {
    ctx.progress(static_cast<double>(it.iteration) / options_.max_iterations, "MSD optimisation");
    ctx.info(iteration_line(it));
  };
  const OptimisationResult result = optimise(target, mesh, options_, on_iteration, [&] { return ctx.cancelled(); });
  for (const RoundLog& round : result.additions)
    ctx.info(fmt::format("{} uncovered regions (largest {:.3g}), {} sites added; {:.3f} s", round.uncovered_regions,
                         round.largest_region_volume, round.sites_added, round.seconds));
  ctx.info(fmt::format("stopped after {} iterations in {} rounds: {}; δ = {:.3g} of the unit box; {} tets in {:.3f} s",
                       result.log.size(), result.rounds, result.stop_reason, result.delta, result.tets,
                       result.seconds_tetrahedralisation));
  ctx.info(fmt::format("final fit of {} primitives: {:.3f} s", result.best.primitives.size(), result.seconds_final_fit));
  medial = skeleton_complex(result.best);
  Summary summary;
  const std::vector<RefinedPrimitive> primitives = final_primitives(target, result.best, summary.refinement, ctx);
  write_outputs(shape, result, primitives, summary, start, ctx);
}

std::vector<RefinedPrimitive> MsdStage::final_primitives(const TargetMesh& target, const Diagram& best,
                                                         RefinementSummary& summary, Context& ctx) const {
  if (!refine_) return unrefined_primitives(best.primitives);
  summary.enabled = true;
  const auto start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  std::vector<RefinedPrimitive> refined = refine_primitives(best.primitives, target, refine_options_);
  summary.seconds = seconds_since(start);
  summary.cpu_seconds = cpu_seconds_since(cpu_start);
  for (std::size_t k = 0; k < refined.size(); ++k) {
    if (!best.primitives[k].fitted) continue;
    if (refined[k].refined) {
      ++summary.refined;
      continue;
    }
    ++summary.unrefined;
    summary.notes.emplace_back(k, refined[k].note);
    ctx.info(fmt::format("primitive {} left unrefined (its fitted T_P is kept): {}", k, refined[k].note));
  }
  ctx.info(fmt::format("refinement: {} primitives refined, {} left unrefined; {:.3f} s ({:.3f} s CPU)", summary.refined,
                       summary.unrefined, summary.seconds, summary.cpu_seconds));
  return refined;
}

void MsdStage::write_outputs(const Shape& shape, const OptimisationResult& result,
                             const std::vector<RefinedPrimitive>& primitives, Summary& summary,
                             Clock::time_point start, Context& ctx) {
  const Diagram& best = result.best;
  summary.counts = count_elements(best, primitives);
  summary.input_vertices = shape.mesh.vertices.size();
  summary.input_triangles = shape.mesh.faces.size();
  summary.covered_area = -best.coverage.energy;
  summary.covered_vertices =
      static_cast<double>(std::count(best.coverage.covered.begin(), best.coverage.covered.end(), 1)) /
      std::max<std::size_t>(1, best.coverage.covered.size());
  summary.result = &result;
  summary.radius_rule = kRadiusRule;
  if (write_primitives_)
    ctx.write_output(ctx.stage_id() + "_primitives.ply",
                     [&](std::ostream& out) { write_primitives_ply(out, primitives, shape.to_input); });
  if (reconstruction_ != ReconstructionMode::None) publish_reconstruction(shape, primitives, summary, ctx);
  const Counts& c = summary.counts;
  ctx.publish(kRepresentationSize, RepresentationSize{c.discrete, c.continuous, kCountRule});
  summary.seconds_total = seconds_since(start);
  ctx.write_output(ctx.stage_id() + "_msd.json", [&](std::ostream& out) { write_summary_json(out, summary); });
  ctx.info(fmt::format("MSD: {} vertices, {} unique edges, {} triangles (N_d {}, N_c {}), coverage {:.4f} of the "
                       "area, {} failed primitives",
                       c.vertices, c.edges, c.triangles, c.discrete, c.continuous, summary.covered_area,
                       c.failed_primitives));
}

void MsdStage::publish_reconstruction(const Shape& shape, const std::vector<RefinedPrimitive>& primitives,
                                      Summary& summary, Context& ctx) const {
  const auto start = Clock::now();
  const std::vector<SurfaceMesh> solids = refined_surfaces(primitives);
  ReconstructedSurface rebuilt = reconstruction_ == ReconstructionMode::Union
                                     ? reconstruct_union(solids, shape.to_input, union_)
                                     : reconstruct_sdf(solids, shape.to_input, sdf_);
  summary.seconds_reconstruction = seconds_since(start);
  summary.reconstruction = rebuilt.method;
  ctx.info(fmt::format("reconstruction Ŝ: {}; {} vertices, {} triangles, {:.3f} s", rebuilt.method,
                       rebuilt.surface.vertices.size(), rebuilt.surface.faces.size(), summary.seconds_reconstruction));
  ctx.publish(kReconstructedSurface, std::move(rebuilt));
}

StageInfo MsdMedialStage::describe() {
  return {"msd_medial", "Reads the medial mesh M from the MSD authors' JSON (input-ma.json); radii = distance to S",
          "docs/plugins/msd.md"};
}

void MsdMedialStage::declare(ParamBinder& p) {
  p.add("medial_file", medial_file_, "path of the authors' medial-mesh JSON (vertices, edges, triangles)");
}

void MsdMedialStage::check_params() const {
  if (medial_file_.empty())
    throw std::invalid_argument("`medial_file` is empty; give the path of the authors' input-ma.json");
}

MedialComplex MsdMedialStage::extract(const Shape& shape, Context& ctx) {
  MedialComplex medial = read_medial_json(medial_file_);
  const Similarity to_current = shape.to_input.inverse();  // the file is in the input mesh's frame
  for (Vec3& c : medial.centres) c = to_current.apply(c);
  if (!shape.mesh.faces.empty()) {
    const TargetMesh target(shape.mesh);
    for (std::size_t v = 0; v < medial.num_vertices(); ++v) medial.radii[v] = target.distance(medial.centres[v]);
  }
  ctx.info(fmt::format("{}: {} vertices, {} edges, {} triangles", medial_file_, medial.num_vertices(),
                       medial.edges.size(), medial.faces.size()));
  return medial;
}

}  // namespace medax::msd
