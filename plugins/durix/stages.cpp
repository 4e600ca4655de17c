// The stages of the durix package: parameters, checks against the data, calls into the
// algorithms (remesh_fallback.cpp, durix.cpp), logs and extra outputs.
#include "stages.hpp"

#include "sheet_graph.hpp"

#include "remesh_fallback.hpp"

#include <medax/services/kdtree.hpp>
#include <medax/services/mesh_check.hpp>

#include <fmt/format.h>

#include <ostream>
#include <stdexcept>

namespace medax::durix {

// ---------------------------------------------------------------------------------------------
// durix_epsilon

StageInfo EpsilonOracleStage::describe() {
  return {"durix_epsilon",
          "Durix ε-oracle: a surface region is insignificant when its vertices lie within ε of the medial "
          "balls of the path that attaches it; alone, counts the surface vertices each inflated ball covers",
          "docs/plugins/durix.md#durix_epsilon",
          {ParamSpec::real("epsilon", 0.01, "tolerance ε (the paper's default: 1% of the bounding-box diagonal)")
               .at_least(0)
               .in_unit("bbox diagonal, or shape units when absolute"),
           ParamSpec::choice("mode", "relative", {"relative", "absolute"},
                             "relative: ε times the bounding-box diagonal of the shape; absolute: ε as given")}};
}

double EpsilonOracleStage::absolute_epsilon(const Shape& shape) const {
  const double eps = params().real("epsilon");
  return params().text("mode") == "absolute" ? eps : eps * bbox_diagonal(shape.mesh.vertices);
}

std::unique_ptr<RegionOracle> EpsilonOracleStage::make_oracle(const Shape& shape) const {
  return std::make_unique<EpsilonOracle>(absolute_epsilon(shape));
}

void EpsilonOracleStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const std::vector<Vec3>& points = shape.mesh.empty() ? shape.samples.points : shape.mesh.vertices;
  if (points.empty()) throw std::invalid_argument("durix_epsilon: the shape has no surface points to cover");
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
          "docs/plugins/durix.md#delaunay_surface",
          {ParamSpec::choice("method", "dzm07", {"dzm07", "remesh"},
                             "dzm07: flips and splits, keeps the input vertices; remesh: resample the surface with "
                             "Mesh_3 (the input vertices are not kept)"),
           ParamSpec::choice("fallback", "remesh", {"remesh", "none"},
                             "when dzm07 fails: remesh (with a warning) or refuse"),
           ParamSpec::real("feature_angle", 20.0,
                           "dzm07: flip a non-Delaunay edge only where its faces bend less than this; split it "
                           "otherwise")
               .range(0, 90)
               .in_unit("degrees"),
           ParamSpec::boolean("flips", true, "dzm07: allow flips (false: splits only, the surface never moves)"),
           ParamSpec::real("max_insertions", 4.0,
                           "dzm07: give up after inserting this many points per input vertex (+1000)")
               .at_least(0)
               .in_unit("ratio"),
           ParamSpec::real("remesh_facet_size", RemeshOptions{}.facet_size,
                           "remesh: largest surface Delaunay ball radius, times the input's mean edge length")
               .at_least(1e-3)
               .in_unit("mean edge length"),
           ParamSpec::real("remesh_facet_distance", RemeshOptions{}.facet_distance,
                           "remesh: largest distance from a facet's circumcentre to the input surface")
               .range(1e-5, 0.1)
               .in_unit("bbox diagonal"),
           ParamSpec::real("remesh_facet_angle", RemeshOptions{}.facet_angle_deg,
                           "remesh: smallest facet angle (Mesh_3 terminates up to 30)")
               .range(1, 30)
               .in_unit("degrees"),
           ParamSpec::integer("remesh_attempts", DelaunaySurfaceOptions{}.remesh_attempts,
                              "remesh: attempts; after a lost handle or component at half the size and distance, "
                              "after a run to the vertex cap or a mesher error at twice the distance")
               .range(1, 6),
           ParamSpec::boolean("check_self_intersections", true,
                              "refuse self-intersecting meshes (the exact test; the solid is undefined otherwise)")}};
}

void DelaunaySurfaceStage::prepare(const Scene& scene) const {
  if (scene.shape.mesh.empty())
    throw std::invalid_argument("delaunay_surface: the shape has no surface mesh (it converts meshes, not samples)");
}

void DelaunaySurfaceStage::condition(Shape& shape, Context& ctx) {
  if (shape.mesh.empty()) throw std::invalid_argument("delaunay_surface: the shape has no surface mesh");
  services::MeshCheckOptions check_options;
  check_options.self_intersections = params().boolean("check_self_intersections");
  const services::MeshReport report = services::check_mesh(shape.mesh, check_options);
  ctx.info("input: " + report.summary());
  if (!report.ok())
    throw std::runtime_error("delaunay_surface: cannot convert this mesh: " + report.describe_problems() +
                             " (a Delaunay mesh must bound a solid: closed, manifold, outward, without duplicates; "
                             "put a `repair` stage before)");
  const DelaunaySurfaceOptions options = conversion_options();
  DelaunaySurfaceResult r;
  try {
    r = make_delaunay_surface(
        shape.mesh, options, [&ctx] { ctx.check_cancelled(); }, [&ctx](const std::string& line) { ctx.info(line); });
  } catch (const Cancelled&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("delaunay_surface: cannot convert this mesh: ") + e.what());
  }
  if (r.method == DelaunayMethod::Dzm07) {
    if (!log_dzm07(r.dzm07, ctx)) return;
  } else {
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
  shape.mesh = std::move(r.mesh);
  if (!shape.samples.empty()) {
    ctx.warn("dropped the samples taken before delaunay_surface (the surface changed); put `sample` after it");
    shape.samples = {};
  }
}

DelaunaySurfaceOptions DelaunaySurfaceStage::conversion_options() const {
  DelaunaySurfaceOptions options;
  options.method = params().text("method") == "remesh" ? DelaunayMethod::Remesh : DelaunayMethod::Dzm07;
  options.fallback_to_remesh = params().text("fallback") == "remesh";
  options.dzm07.feature_angle_deg = params().real("feature_angle");
  options.dzm07.flips = params().boolean("flips");
  options.dzm07.max_insertions_factor = params().real("max_insertions");
  options.remesh.facet_size = params().real("remesh_facet_size");
  options.remesh.facet_distance = params().real("remesh_facet_distance");
  options.remesh.facet_angle_deg = params().real("remesh_facet_angle");
  options.remesh_attempts = static_cast<int>(params().integer("remesh_attempts"));
  return options;
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

// ---------------------------------------------------------------------------------------------
// durix

StageInfo DurixStage::describe() {
  return {"durix",
          "Durix et al. 2023 clean medial axis: sheet propagation over the interior Delaunay cells of a Delaunay "
          "mesh, ε-filtration of sheets with carving of the surface, sheets, boundary and singular paths",
          "docs/plugins/durix.md#durix",
          {ParamSpec::stage("oracle", Role::Significance, "durix_epsilon",
                            "the significance test of a region beyond a singular path (a durix package oracle)"),
           ParamSpec::boolean("preserve_topology", true,
                              "refuse a carving that changes the Euler characteristic of the working surface"),
           ParamSpec::boolean("simplify_boundaries", true, "carve boundary spikes covered within ε (§4.6)"),
           ParamSpec::boolean("remove_outside_centres", true,
                              "carve surface cells whose ball is centred outside the input, when ε allows (Appendix A)"),
           ParamSpec::boolean("split_problematic", true, "split sheets at problematic edges (§4.7)"),
           ParamSpec::integer("max_passes", 10, "fixpoint: passes of propagation and carving at most").range(1, 1000),
           ParamSpec::boolean("write_surface", true,
                              "write the working surface M_w as <id>_surface.ply (input frame)"),
           ParamSpec::boolean("write_segmentation", true,
                              "write the surface segmentation (sheet per face) as <id>_segmentation.ply"),
           ParamSpec::boolean("write_sheet_graph", true,
                              "write the sheets and their adjacency through singular paths as <id>_sheets.json")}};
}

void DurixStage::prepare(const Scene& scene) const { check(scene.shape); }

void DurixStage::check(const Shape& shape) const {
  if (shape.mesh.empty() || shape.mesh.vertices.size() < 4)
    throw std::invalid_argument("durix: the shape has no surface mesh (at least 4 vertices); durix needs a closed "
                                "Delaunay mesh (`delaunay_surface`)");
  if (!dynamic_cast<const DurixOracle*>(params().stage_ref("oracle").instance.get()))
    throw std::invalid_argument("durix: parameter 'oracle' must be a durix oracle such as `durix_epsilon`, not '" +
                                params().stage_ref("oracle").plugin + "'");
}

MedialComplex DurixStage::extract(const Shape& shape, Context& ctx) {
  check(shape);
  const auto& oracle_stage = params().stage<DurixOracle>("oracle");
  const std::unique_ptr<RegionOracle> oracle = oracle_stage.make_oracle(shape);
  DurixOptions options;
  options.preserve_topology = params().boolean("preserve_topology");
  options.simplify_boundaries = params().boolean("simplify_boundaries");
  options.remove_outside_centres = params().boolean("remove_outside_centres");
  options.split_problematic = params().boolean("split_problematic");
  options.max_passes = static_cast<int>(params().integer("max_passes"));
  try {
    last_ = durix_medial_axis(
        shape.mesh, *oracle, options, [&ctx](double f, std::string_view what) { ctx.progress(f, what); },
        [&ctx] { ctx.check_cancelled(); });
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("durix: ") + e.what());
  }
  const DurixReport& r = last_.report;
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

  const Similarity& to_input = shape.to_input;
  if (params().boolean("write_surface")) {
    ctx.write_output(id() + "_surface.ply", [&](std::ostream& out) {
      DurixResult copy;
      copy.surface = last_.surface;
      for (Vec3& p : copy.surface.vertices) p = to_input.apply(p);
      copy.surface_vertex = last_.surface_vertex;
      copy.surface_face_node = last_.surface_face_node;
      copy.surface_face_sheet = last_.surface_face_sheet;
      write_surface_ply(out, copy);
    });
  }
  if (params().boolean("write_segmentation")) {
    ctx.write_output(id() + "_segmentation.ply", [&](std::ostream& out) {
      SurfaceMesh mesh = shape.mesh;
      for (Vec3& p : mesh.vertices) p = to_input.apply(p);
      write_segmentation_ply(out, mesh, last_);
    });
  }
  if (params().boolean("write_sheet_graph"))
    ctx.write_output(id() + "_sheets.json", [&](std::ostream& out) {
      write_sheet_graph_json(out, sheet_graph(last_.medial), to_input.scale);
    });
  return last_.medial;
}

ParamSet durix_params(double epsilon) {
  ParamSet params = default_params(DurixStage::describe().params);
  auto ref = std::make_shared<StageRef>();
  ref->plugin = "durix_epsilon";
  ref->params = default_params(EpsilonOracleStage::describe().params);
  ref->params.set("epsilon", epsilon);
  auto oracle = std::make_shared<EpsilonOracleStage>();
  oracle->set_id("durix_epsilon");
  oracle->configure(ref->params);
  ref->instance = oracle;
  params.set("oracle", ref);
  return params;
}

}  // namespace medax::durix
