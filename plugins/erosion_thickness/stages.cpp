#include "stages.hpp"

#include "erosion_thickness.hpp"
#include "local_measures.hpp"
#include "pure_complex.hpp"

#include <medax/services/topology.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

namespace medax::et {

namespace {

constexpr const char* kDoc = "docs/plugins/erosion_thickness.md";

std::vector<ParamSpec> burn_params() {
  return {ParamSpec::real("omega", 0.004,
                          "Largest spacing of graph nodes on an edge, as a fraction of the reference length "
                          "(paper: 0.004 of the unit max bbox side)")
              .range(1e-6, 1.0)
              .in_unit("fraction of reference length"),
          ParamSpec::integer("min_samples", 1, "Least number of samples per edge (the paper's error bound needs 1)")
              .range(0, 1000),
          ParamSpec::choice("relative_to", "shape_max_side", {"shape_max_side", "complex_max_side", "absolute"},
                            "Reference length of omega and the thresholds: the longest bbox side of the shape "
                            "(of the complex when the shape is empty), of the complex, or 1")};
}

std::function<void()> canceller(Context& ctx) {
  return [&ctx] { ctx.check_cancelled(); };
}

std::string topology_text(const services::ComplexTopology& t) {
  return fmt::format("V {} E {} F {}, chi {}, b0 {} b1 {} b2 {}", t.vertices, t.edges, t.faces, t.euler, t.b0, t.b1,
                     t.b2);
}

bool same_topology(const services::ComplexTopology& a, const services::ComplexTopology& b) {
  return a.euler == b.euler && a.b0 == b.b0 && a.b1 == b.b1 && a.b2 == b.b2;
}

std::unique_ptr<EtRun> burn_for(const ParamSet& p, const Shape& shape, const MedialComplex& medial, Context& ctx,
                                double* length) {
  const double L = reference_length(shape, medial, p.text("relative_to"));
  if (length) *length = L;
  const double omega = p.real("omega") * L;
  auto run = run_erosion_thickness(medial, omega, static_cast<int>(p.integer("min_samples")), canceller(ctx));
  const BurnGraph& g = run->graph;
  ctx.info(fmt::format("graph: omega {:g} (reference length {:g}), {} triangles, {} nodes ({} samples), {} sectors, "
                       "{} arcs; built in {:.3f} s",
                       omega, L, run->complex.num_triangles(), g.num_nodes(), g.num_nodes() - g.num_vertices(),
                       g.num_sectors(), g.count_arcs(), run->seconds_graph));
  std::size_t unburned = 0;
  for (double b : run->burn.bt) unburned += std::isinf(b);
  ctx.info(fmt::format("burn: {} pops, {} relaxations in {:.3f} s; {} nodes never burn (closed surfaces)",
                       run->burn.pops, run->burn.relaxations, run->seconds_burn, unburned));
  return run;
}

}  // namespace

// ---- erosion_thickness ---------------------------------------------------------------------

StageInfo ErosionThicknessStage::describe() {
  auto params = burn_params();
  params.push_back(ParamSpec::boolean("write_forest", false,
                                      "Write the burn forest (every primary arc) to <id>_burn_forest.obj in the run folder"));
  return {"erosion_thickness",
          "Burn time and Erosion Thickness (Yan et al. 2016) per vertex: fields bt, et (+ face mean et)", kDoc,
          std::move(params)};
}

void ErosionThicknessStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  if (medial.faces.empty()) ctx.warn("the complex has no triangles: every vertex is its own boundary (ET = 0)");
  const auto run = burn_for(params(), shape, medial, ctx, nullptr);
  store_erosion_thickness(*run, medial);
  const auto& et = medial.vertex_props.fields.get("et");
  std::size_t negative = 0, infinite = 0;
  double lo = kInf, hi = -kInf;
  for (double v : et) {
    if (std::isinf(v)) {
      ++infinite;
      continue;
    }
    negative += v < -1e-12;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  std::size_t steep = 0;
  for (const Segment& e : run->complex.edges)
    steep += std::abs(medial.radii[e[0]] - medial.radii[e[1]]) > (medial.centres[e[0]] - medial.centres[e[1]]).norm();
  ctx.info(fmt::format("et in [{:g}, {:g}]; {} vertices with et = inf; {} edges where |dR| > length", lo, hi, infinite,
                       steep));
  if (negative > 0)
    ctx.warn(fmt::format("{} of {} vertices ({:.2f}%, lowest ET {:g}) have ET < 0: the interpolated radius varies "
                         "faster than distance along some arcs ({} edges, and arcs across skinny triangles; the "
                         "paper's g > 1), so fire reaches them before their own ignition time",
                         negative, et.size(), 100.0 * negative / std::max<std::size_t>(1, et.size()), lo, steep));
  if (params().boolean("write_forest")) {
    const std::string name = (id().empty() ? std::string("erosion_thickness") : id()) + "_burn_forest.obj";
    ctx.write_output(name, [&run](std::ostream& out) {
      const BurnGraph& g = run->graph;
      out << "# medax erosion_thickness: burn forest (one line per primary arc)\n";
      for (const Vec3& p : g.pos) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
      for (Index n = 0; n < g.num_nodes(); ++n)
        for (Index s = g.sector_begin[n]; s < g.sector_begin[n + 1]; ++s)
          if (run->burn.prime_node[s] != kNone) out << "l " << run->burn.prime_node[s] + 1 << ' ' << n + 1 << '\n';
    });
  }
}

// ---- local measures ------------------------------------------------------------------------

namespace {
void add_face_mean(MedialComplex& medial, const std::string& name, const std::vector<double>& values) {
  auto& f = medial.face_props.fields.add(name, medial.faces.size());
  for (std::size_t i = 0; i < medial.faces.size(); ++i)
    f[i] = (values[medial.faces[i][0]] + values[medial.faces[i][1]] + values[medial.faces[i][2]]) / 3;
}
ParamSpec tolerance_param() {
  return ParamSpec::real("tolerance", 1e-6,
                         "Without generators: surface points within (1 + tolerance) x the nearest distance "
                         "count as generators")
      .at_least(0)
      .in_unit("ratio");
}
}  // namespace

StageInfo RadiusMeasureStage::describe() {
  return {"radius_measure", "The medial radius R as a significance field `radius` (vertex; face mean)", kDoc, {}};
}

void RadiusMeasureStage::measure(const Shape&, MedialComplex& medial, Context& ctx) {
  medial.vertex_props.fields.add("radius", medial.num_vertices()) = medial.radii;
  add_face_mean(medial, "radius", medial.radii);
  ctx.info(fmt::format("radius on {} vertices", medial.num_vertices()));
}

StageInfo ObjectAngleStage::describe() {
  return {"object_angle",
          "Object angle: largest angle at the centre between two generators, field `object_angle` (radians)",
          kDoc,
          {tolerance_param()}};
}

void ObjectAngleStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  std::string source;
  const auto gens = medial_generators(shape, medial, params().real("tolerance"), &source);
  std::vector<double> angle(medial.num_vertices());
  std::size_t single = 0;
  for (std::size_t v = 0; v < angle.size(); ++v) {
    angle[v] = max_pairwise_angle(medial.centres[v], gens[v]);
    single += gens[v].size() < 2;
  }
  medial.vertex_props.fields.add("object_angle", angle.size()) = angle;
  add_face_mean(medial, "object_angle", angle);
  ctx.info(fmt::format("object angle from {}; {} vertices with fewer than 2 generators (angle 0)", source, single));
}

StageInfo CircumradiusStage::describe() {
  return {"circumradius",
          "Circumradius of the generators (the lambda of the lambda-medial axis), field `circumradius`",
          kDoc,
          {tolerance_param()}};
}

void CircumradiusStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  std::string source;
  const auto gens = medial_generators(shape, medial, params().real("tolerance"), &source);
  std::vector<double> lambda(medial.num_vertices());
  for (std::size_t v = 0; v < lambda.size(); ++v) lambda[v] = std::max(0.0, min_enclosing_ball(gens[v]).radius);
  medial.vertex_props.fields.add("circumradius", lambda.size()) = lambda;
  add_face_mean(medial, "circumradius", lambda);
  ctx.info(fmt::format("circumradius from {}", source));
}

// ---- et_medial_curves ----------------------------------------------------------------------

StageInfo MedialCurvesStage::describe() {
  return {"et_medial_curves",
          "Medial curves dual to the burn trees (Yan et al. 2016, §7), with ET_C; replaces the complex by the curves",
          kDoc, burn_params()};
}

void MedialCurvesStage::connect(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology before = services::complex_topology(medial);
  const auto run = burn_for(params(), shape, medial, ctx, nullptr);
  if (!run->loose_edges.empty())
    ctx.warn(fmt::format("{} edges bound no triangle and are left out of the curves; run `pure_complex` first",
                         run->loose_edges.size()));
  const Subdivision sub = build_subdivision(run->graph, run->burn);
  const MedialCurves curves = extract_medial_curves(run->graph, sub);
  ctx.info(fmt::format("subdivision: {} faces, {} curve edges, {} bridges; {} closed-surface triangles kept",
                       sub.num_faces(), sub.curve_edges.size(), sub.bridges, sub.residue_triangles));
  if (sub.crossing_arcs > 0)
    ctx.warn(fmt::format("{} burn arcs crossed another in their triangle (round-off) and were left out: the "
                         "curves may not be homotopy equivalent to the complex",
                         sub.crossing_arcs));
  store_medial_curves(curves, medial);
  const services::ComplexTopology after = services::complex_topology(medial);
  ctx.info("complex: " + topology_text(before) + "; curves: " + topology_text(after));
  if (run->loose_edges.empty() && !same_topology(before, after))
    ctx.warn("the curves' topology differs from the complex's (see the line above)");
}

// ---- et_skeleton ---------------------------------------------------------------------------

StageInfo EtSkeletonStage::describe() {
  auto params = burn_params();
  params.push_back(ParamSpec::real("theta2", 0.02,
                                   "Sheets whose ET exceeds theta2 x L are kept (paper: 0.01-0.03; .inf keeps none)")
                       .at_least(0)
                       .in_unit("fraction of reference length"));
  params.push_back(ParamSpec::real("theta1", 0.04,
                                   "Curves whose ET_C exceeds theta1 x L are kept (paper: 0.02-0.06; .inf keeps none)")
                       .at_least(0)
                       .in_unit("fraction of reference length"));
  params.push_back(ParamSpec::real("phi2", 0.0005, "Kept sheet components of area below phi2 x L^2 are dropped")
                       .at_least(0)
                       .in_unit("fraction of reference area"));
  params.push_back(ParamSpec::real("phi1", 0.0, "Kept curve components of length below phi1 x L are dropped")
                       .at_least(0)
                       .in_unit("fraction of reference length"));
  return {"et_skeleton",
          "Topology-preserving skeleton of sheets (ET >= theta2) and curves (ET_C >= theta1) (Yan et al. 2016, §7.3)",
          kDoc, std::move(params)};
}

void EtSkeletonStage::simplify(const Shape& shape, MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology before = services::complex_topology(medial);
  double L = 1;
  const auto run = burn_for(params(), shape, medial, ctx, &L);
  const Subdivision sub = build_subdivision(run->graph, run->burn);
  if (sub.crossing_arcs > 0)
    ctx.warn(fmt::format("{} burn arcs crossed another in their triangle (round-off) and were left out",
                         sub.crossing_arcs));
  SkeletonOptions o;
  o.theta2 = params().real("theta2") * L;
  o.theta1 = params().real("theta1") * L;
  o.phi2 = params().real("phi2") * L * L;
  o.phi1 = params().real("phi1") * L;
  const Skeleton sk = compute_skeleton(run->graph, sub, run->loose_edges, o);
  ctx.info(fmt::format("refined cell complex: {} points, {} 1-cells, {} wedges; protected {} wedges, {} curve "
                       "cells ({} sheet and {} curve components below the size limits dropped); {:.3f} s to build, "
                       "{:.3f} s to contract; {} input triangles written whole",
                       sk.refined_vertices, sk.refined_edges, sk.refined_faces, sk.protected_faces,
                       sk.protected_curve_edges, sk.dropped_sheet_components, sk.dropped_curve_components,
                       sk.seconds_refine, sk.seconds_contract, sk.coarse_triangles));
  store_skeleton(sk, medial);
  const services::ComplexTopology after = services::complex_topology(medial);
  ctx.info("input: " + topology_text(before) + "; skeleton: " + topology_text(after));
  if (!same_topology(before, after)) ctx.warn("the skeleton's topology differs from the input's (see the line above)");
}

// ---- pure_complex --------------------------------------------------------------------------

StageInfo PureComplexStage::describe() {
  return {"pure_complex",
          "Clean a medial complex into a pure 2-complex: weld, drop degenerate/duplicate triangles, dangling "
          "edges and isolated vertices",
          kDoc,
          {ParamSpec::real("weld_tolerance", 1e-9,
                           "Centres closer than this fraction of the complex's longest bbox side are welded "
                           "(0: only identical centres; Voronoi vertices of cospherical points differ by round-off)")
               .range(0, 0.1)
               .in_unit("fraction of complex max side")}};
}

void PureComplexStage::simplify(const Shape&, MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology before = services::complex_topology(medial);
  double side = 0;
  if (!medial.centres.empty()) {
    Vec3 lo = medial.centres[0], hi = lo;
    for (const Vec3& p : medial.centres) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    side = (hi - lo).maxCoeff();
  }
  const PureComplexReport r = make_pure_complex(medial, params().real("weld_tolerance") * side);
  const services::ComplexTopology after = services::complex_topology(medial);
  ctx.info(fmt::format("welded {} vertices (largest radius gap {:g}), dropped {} degenerate and {} duplicate "
                       "triangles, {} dangling edges, {} isolated vertices",
                       r.welded_vertices, r.max_weld_radius_gap, r.degenerate_faces, r.duplicate_faces,
                       r.dangling_edges, r.isolated_vertices));
  ctx.info("before: " + topology_text(before) + "; after: " + topology_text(after));
  if (!same_topology(before, after))
    ctx.warn("dropping dangling edges or isolated vertices changed the topology (see the line above)");
}

}  // namespace medax::et
