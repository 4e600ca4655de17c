// The stages of the durix package: parameters, checks against the data, calls into the
// algorithms (remesh_fallback.cpp, durix.cpp), logs and extra outputs.
#include "stages.hpp"

#include "sheet_graph.hpp"

#include <medax/services/kdtree.hpp>

#include <fmt/format.h>

#include <ostream>
#include <stdexcept>

namespace medax::durix {

// ---------------------------------------------------------------------------------------------
// durix_epsilon

namespace {
const std::vector<Vec3>& surface_points(const Shape& shape) {
  return shape.mesh.empty() ? shape.samples.points : shape.mesh.vertices;
}
}  // namespace

StageInfo EpsilonOracleStage::describe() {
  return {"durix_epsilon",
          "Durix ε-oracle: a surface region is insignificant when its vertices lie within ε of the medial "
          "balls of the path that attaches it; alone, counts the surface vertices each inflated ball covers",
          "docs/plugins/durix.md#durix_epsilon"};
}

void EpsilonOracleStage::declare(ParamBinder& p) {
  p.add("epsilon", epsilon_, "tolerance ε (the paper's default: 1% of the bounding-box diagonal)")
      .at_least(0)
      .in_unit("bbox diagonal, or shape units when absolute");
  p.add("mode", mode_, {{"relative", EpsilonMode::Relative}, {"absolute", EpsilonMode::Absolute}},
        "relative: ε times the bounding-box diagonal of the shape; absolute: ε as given");
}

double EpsilonOracleStage::absolute_epsilon(const Shape& shape) const {
  return mode_ == EpsilonMode::Absolute ? epsilon_ : epsilon_ * bbox_diagonal(shape.mesh.vertices);
}

std::unique_ptr<RegionOracle> EpsilonOracleStage::make_oracle(const Shape& shape) const {
  return std::make_unique<EpsilonOracle>(absolute_epsilon(shape));
}

void EpsilonOracleStage::check_scene(const Scene& scene) const {
  if (surface_points(scene.shape).empty()) throw std::invalid_argument("the shape has no surface points to cover");
}

void EpsilonOracleStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const std::vector<Vec3>& points = surface_points(shape);
  if (points.empty()) throw std::invalid_argument("the shape has no surface points to cover");
  const double eps = absolute_epsilon(shape);
  const std::size_t nv = medial.num_vertices();
  services::PointIndex index(points);
  std::vector<std::uint32_t> cover(points.size(), 0);
  std::vector<std::vector<Index>> covered(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    if ((i & 1023) == 0) ctx.check_cancelled();
    for (const auto& [p, dist] : index.within(medial.centres[i], medial.radii[i] + eps)) {
      if (dist >= medial.radii[i] + eps) continue;
      covered[i].push_back(p);
      ++cover[p];
    }
  }
  auto& total = medial.vertex_props.fields.add("durix_coverage", nv);
  auto& unique = medial.vertex_props.fields.add("durix_unique_coverage", nv);
  std::size_t uncovered = 0;
  for (std::size_t i = 0; i < nv; ++i) {
    total[i] = static_cast<double>(covered[i].size());
    for (Index p : covered[i]) unique[i] += cover[p] == 1;
  }
  for (std::uint32_t c : cover) uncovered += c == 0;
  ctx.info(fmt::format("ε = {:.6g}: {} of {} surface points covered by no inflated ball", eps, uncovered,
                       points.size()));
}

// ---------------------------------------------------------------------------------------------
// delaunay_surface

StageInfo DelaunaySurfaceStage::describe() {
  return {"delaunay_surface",
          "Makes the mesh a Delaunay mesh (every triangle a facet of the Delaunay tetrahedralization of its "
          "vertices) by edge flips and splits (Dyer, Zhang, Möller 2007), or by a restricted-Delaunay remesh "
          "(CGAL Mesh_3) where they fail; verified, refuses what it cannot convert",
          "docs/plugins/durix.md#delaunay_surface"};
}

void DelaunaySurfaceStage::declare(ParamBinder& p) {
  p.add("method", options_.method, {{"dzm07", DelaunayMethod::Dzm07}, {"remesh", DelaunayMethod::Remesh}},
        "dzm07: flips and splits, keeps the input vertices; remesh: resample the surface with Mesh_3 (the input "
        "vertices are not kept)");
  p.add("fallback", options_.fallback, {{"remesh", DelaunayFallback::Remesh}, {"none", DelaunayFallback::None}},
        "when dzm07 fails: remesh (with a warning) or refuse");
  p.add("feature_angle", options_.dzm07.feature_angle_deg,
        "dzm07: flip a non-Delaunay edge only where its faces bend less than this; split it otherwise")
      .range(0, 90)
      .in_unit("degrees");
  p.add("flips", options_.dzm07.flips,
        "dzm07: allow flips (false: splits only; the surface never moves, but the splits may not converge)");
  p.add("max_insertions", options_.dzm07.max_insertions_factor,
        "dzm07: give up after inserting this many points per input vertex (+1000)")
      .at_least(0)
      .in_unit("ratio");
  p.add("remesh_facet_size", options_.remesh.facet_size,
        "remesh: largest surface Delaunay ball radius, times the input's mean edge length (0.85: about the "
        "input's vertex count on organic meshes)")
      .at_least(1e-3)
      .in_unit("mean edge length");
  p.add("remesh_facet_distance", options_.remesh.facet_distance,
        "remesh: largest distance from a facet's circumcentre to the input surface; sets the vertex count of CAD "
        "meshes (their sharp creases are not protected)")
      .range(1e-5, 0.1)
      .in_unit("bbox diagonal");
  p.add("remesh_facet_angle", options_.remesh.facet_angle_deg,
        "remesh: smallest facet angle (Mesh_3 terminates up to 30)")
      .range(1, 30)
      .in_unit("degrees");
  p.add("remesh_attempts", options_.remesh_attempts,
        "remesh: attempts; after a lost handle or component at half the size and distance, after a run to the "
        "vertex cap or a mesher error at twice the distance")
      .range(1, 6);
  p.add("check_self_intersections", check_options_.self_intersections,
        "refuse self-intersecting meshes (the exact test; the solid is undefined otherwise)");
}

void DelaunaySurfaceStage::check_scene(const Scene& scene) const {
  if (scene.shape.mesh.empty())
    throw std::invalid_argument("the shape has no surface mesh (this stage converts meshes, not samples; "
                                "`reconstruct_mesh` makes one of a point cloud)");
}

void DelaunaySurfaceStage::check_input(const SurfaceMesh& mesh, Context& ctx) const {
  if (mesh.empty())
    throw std::invalid_argument("the shape has no surface mesh (`reconstruct_mesh` makes one of a point cloud)");
  const services::MeshReport report = services::check_mesh(mesh, check_options_);
  ctx.info("input: " + report.summary());
  if (!report.ok())
    throw std::runtime_error("cannot convert this mesh: " + report.describe_problems() +
                             " (a Delaunay mesh must bound a solid: closed, manifold, outward, without duplicates; "
                             "put a `repair` stage before)");
}

void DelaunaySurfaceStage::condition(Shape& shape, Context& ctx) {
  check_input(shape.mesh, ctx);
  DelaunaySurfaceResult r;
  try {
    r = make_delaunay_surface(
        shape.mesh, options_, [&ctx] { ctx.check_cancelled(); }, [&ctx](const std::string& line) { ctx.info(line); });
  } catch (const Cancelled&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("cannot convert this mesh: ") + e.what());
  }
  if (r.method == DelaunayMethod::Dzm07) {
    if (!log_dzm07(r.dzm07, ctx)) return;
  } else {
    log_remesh(r, ctx);
  }
  shape.mesh = std::move(r.mesh);
  if (!shape.samples.empty()) {
    ctx.warn("dropped the samples taken before this stage (the surface changed); put `sample` after it");
    shape.samples = {};
  }
}

bool DelaunaySurfaceStage::log_dzm07(const DelaunayMeshReport& r, Context& ctx) {
  ctx.info(fmt::format("{} of {} faces and {} edges were not Delaunay", r.non_delaunay_faces_before, r.input_faces,
                       r.non_delaunay_edges_before));
  if (r.flips + r.edge_splits + r.face_splits == 0) {
    ctx.info("the mesh is already a Delaunay mesh");
    return false;
  }
  ctx.info(fmt::format("{} flips, {} edge splits, {} face splits in {} sweeps: {} vertices, {} faces "
                       "({:.3f} s, of which verification {:.3f} s)",
                       r.flips, r.edge_splits, r.face_splits, r.sweeps, r.output_vertices, r.output_faces, r.seconds,
                       r.seconds_verify));
  return true;
}

void DelaunaySurfaceStage::log_remesh(const DelaunaySurfaceResult& r, Context& ctx) {
  if (!r.dzm07_failure.empty())
    ctx.warn("DZM07 flips and splits failed (" + r.dzm07_failure +
             "); fell back to the restricted-Delaunay remesh (fallback: remesh)");
  const RemeshReport& m = r.remesh;
  ctx.info(fmt::format("remesh (Mesh_3, facet size {:.4g}, distance {:.4g}): {} vertices, {} faces, genus {}, {} "
                       "component(s), from a tetrahedral mesh of {} vertices ({:.3f} s with the checks); the input "
                       "vertices are NOT kept: the surface is resampled",
                       m.facet_size, m.facet_distance, m.output_vertices, m.output_faces, r.genus, r.components,
                       m.mesh3_vertices, r.seconds));
}

// ---------------------------------------------------------------------------------------------
// durix

StageInfo DurixStage::describe() {
  return {"durix",
          "Durix et al. 2023 clean medial axis: sheet propagation over the interior Delaunay cells of a Delaunay "
          "mesh, ε-filtration of sheets with carving of the surface, sheets, boundary and singular paths",
          "docs/plugins/durix.md#durix"};
}

void DurixStage::declare(ParamBinder& p) {
  p.add("oracle", oracle_, "durix_epsilon",
        "the significance test of a region beyond a singular path (a durix package oracle)");
  p.add("preserve_topology", options_.preserve_topology,
        "refuse a carving that changes χ(M_w), the Euler characteristic of the working surface (a topological "
        "form of [R]'s `closable` filter)");
  p.add("simplify_boundaries", options_.simplify_boundaries, "carve covered curve ends and boundary spikes (§4.6)");
  p.add("remove_outside_centres", options_.remove_outside_centres,
        "carve surface cells whose ball is centred outside the input, when ε allows (Appendix A)");
  p.add("split_problematic", options_.split_problematic, "split sheets at problematic edges (§4.7)");
  p.add("max_passes", options_.max_passes, "fixpoint: passes of propagation and carving at most").range(1, 1000);
  p.add("write_surface", write_surface_, "write the working surface M_w as `<id>_surface.ply` (input frame)");
  p.add("write_segmentation", write_segmentation_,
        "write the surface segmentation (sheet per vertex and face) as `<id>_segmentation.ply` (input frame)");
  p.add("write_sheet_graph", write_sheet_graph_,
        "write the sheets and their adjacency through singular paths as `<id>_sheets.json` (published as scene "
        "data `durix.sheet_graph` either way)");
}

void DurixStage::check_params() const {
  if (oracle_.empty()) return;  // filled in by the pipeline, or by the caller before extract()
  if (!oracle_.find())
    throw std::invalid_argument("parameter 'oracle' must be a durix oracle such as `durix_epsilon`, not '" +
                                oracle_.plugin() + "'");
}

void DurixStage::check(const Shape& shape) const {
  if (shape.mesh.empty() || shape.mesh.vertices.size() < 4)
    throw std::invalid_argument("the shape has no surface mesh (at least 4 vertices); this stage needs a closed "
                                "Delaunay mesh (`delaunay_surface`)");
}

MedialComplex DurixStage::extract(const Shape& shape, Context& ctx) {
  check_params();
  check(shape);
  const std::unique_ptr<RegionOracle> oracle = oracle_->make_oracle(shape);
  last_ = durix_medial_axis(
      shape.mesh, *oracle, options_, [&ctx](double f, std::string_view what) { ctx.progress(f, what); },
      [&ctx] { ctx.check_cancelled(); });
  log_report(last_.report, ctx);
  write_outputs(shape, ctx);
  return last_.medial;
}

void DurixStage::log_report(const DurixReport& r, Context& ctx) {
  ctx.info(fmt::format("ε = {:.6g}; {} vertices, {} faces; {} Delaunay cells, {} interior, {} component(s)", r.epsilon,
                       r.input_vertices, r.input_faces, r.dt_cells, r.interior_cells, r.components));
  ctx.info(fmt::format("{} pass(es): {} candidate sheets, {} carved, {} boundary spikes carved; refused: {} not "
                       "separated, {} non-manifold, {} topology; {} unclosed paths",
                       r.passes, r.candidates, r.removals, r.boundary_removals, r.rejected_not_separated,
                       r.rejected_manifold, r.rejected_topology, r.path_failures));
  ctx.info(fmt::format("Appendix A: {} flat cells peeled, {} cells centred outside the input carved, {} nodes "
                       "centred outside left",
                       r.flat_cells_peeled, r.outside_centres_removed, r.outside_centres_left));
  ctx.info(fmt::format("medial axis: {} nodes, {} edges, {} faces; {} sheets, {} curve sheets; problematic edges "
                       "{} found, {} left, {} edges forced singular",
                       r.nodes, r.medial_edges, r.medial_faces, r.sheets, r.curve_sheets, r.problematic_edges,
                       r.problematic_left, r.forced_edges));
  ctx.info(fmt::format("M_w: {} vertices ({} input vertices removed), {} faces; max excess of removed vertices "
                       "over the output balls {:.3g} (ε {:.3g})",
                       r.surface_vertices, r.removed_vertices, r.surface_faces, r.max_removed_excess, r.epsilon));
  ctx.info(fmt::format("time: Delaunay {:.3f} s, propagation {:.3f} s, output {:.3f} s", r.seconds_dual,
                       r.seconds_propagation, r.seconds_output));
  if (r.problematic_left) ctx.warn(fmt::format("{} problematic edges could not be split", r.problematic_left));
}

void DurixStage::write_outputs(const Shape& shape, Context& ctx) const {
  const Similarity& to_input = shape.to_input;
  if (write_surface_)
    ctx.write_output(id() + "_surface.ply", [&](std::ostream& out) { write_surface_ply(out, last_, to_input); });
  if (write_segmentation_)
    ctx.write_output(id() + "_segmentation.ply",
                     [&](std::ostream& out) { write_segmentation_ply(out, shape.mesh, last_, to_input); });
  SheetGraph graph = sheet_graph(last_.medial);
  graph.input_scale = to_input.scale;
  DataKey<SheetGraph> key = kSheetGraph;
  if (!write_sheet_graph_) key.write = nullptr;  // published, not written
  ctx.publish(key, std::move(graph));
}

ParamSet durix_params(double epsilon) {
  ParamSet oracle_params;
  oracle_params.set("epsilon", epsilon);
  auto oracle = std::make_shared<EpsilonOracleStage>();
  oracle->set_id("durix_epsilon");
  oracle->configure(oracle_params);
  auto ref = std::make_shared<StageRef>();
  ref->plugin = "durix_epsilon";
  ref->params = oracle_params;
  ref->instance = oracle;
  ParamSet params;
  params.set("oracle", ref);
  return params;
}

}  // namespace medax::durix
