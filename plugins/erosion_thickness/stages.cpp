#include "stages.hpp"

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

/// Records that this stage replaced the complex, so that a stale burn can name it.
void record_replacement(const MedialComplex& medial, Context& ctx) {
  ctx.publish(kReplacedComplex, fingerprint(medial));
}

/// The burn `erosion_thickness` published, if it is the burn of `medial`; else throws, saying
/// what changed the complex and what to do.
const SharedBurn& burn_of(const SceneData& data, const MedialComplex& medial) {
  const SharedBurn& burn = data.get(kBurnData);  // MissingData names erosion_thickness
  const ComplexFingerprint now = fingerprint(medial);
  if (now == burn.complex) return burn;
  std::string changed = "a stage after it changed the complex";
  if (const ComplexFingerprint* replaced = data.find(kReplacedComplex); replaced && *replaced == now)
    changed = fmt::format("`{}` replaced it", data.publisher(kReplacedComplex.name));
  throw std::invalid_argument(fmt::format("the complex is not the one `{}` burned ({} then, {} now): {}; run "
                                          "`erosion_thickness` right before this stage",
                                          data.publisher(kBurnData.name), to_string(burn.complex), to_string(now),
                                          changed));
}

void log_burn_use(const SceneData& data, const SharedBurn& burn, Context& ctx) {
  ctx.info(fmt::format("burn of `{}`: omega {:g} x L {:g}, {} graph nodes", data.publisher(kBurnData.name),
                       burn.options.omega, burn.length, burn.run->graph.num_nodes()));
}

}  // namespace

// ---- erosion_thickness ---------------------------------------------------------------------

StageInfo ErosionThicknessStage::describe() {
  return {"erosion_thickness",
          "Burn time and Erosion Thickness (Yan et al. 2016) per vertex: fields bt, et (+ face mean et); the burn "
          "feeds et_medial_curves and et_skeleton",
          kDoc};
}

void ErosionThicknessStage::declare(ParamBinder& p) {
  p.add("omega", options_.omega,
        "Largest spacing of graph nodes on an edge, as a fraction of the reference length (paper: 0.004 of the unit "
        "max bbox side)")
      .range(1e-6, 1.0)
      .in_unit("fraction of reference length");
  p.add("min_samples", options_.min_samples, "Least number of samples per edge (the paper's error bound needs 1)")
      .range(0, 1000);
  p.add("relative_to", options_.relative_to, kRelativeToChoices,
        "Reference length L of omega and of et_skeleton's thresholds: the longest bbox side of the shape (of the "
        "complex when the shape is empty), of the complex, or 1");
  p.add("write_forest", write_forest_,
        "Write the burn forest (every primary arc) to `<id>_burn_forest.obj` in the run folder");
}

namespace {

void log_burn(const EtRun& run, double omega, double L, Context& ctx) {
  const BurnGraph& g = run.graph;
  ctx.info(fmt::format("graph: omega {:g} (reference length {:g}), {} triangles, {} nodes ({} samples), {} sectors, "
                       "{} arcs; built in {:.3f} s",
                       omega, L, run.complex.num_triangles(), g.num_nodes(), g.num_nodes() - g.num_vertices(),
                       g.num_sectors(), g.count_arcs(), run.seconds_graph));
  const auto unburned = std::count_if(run.burn.bt.begin(), run.burn.bt.end(), [](double b) { return std::isinf(b); });
  ctx.info(fmt::format("burn: {} pops, {} relaxations in {:.3f} s; {} nodes never burn (closed surfaces)",
                       run.burn.pops, run.burn.relaxations, run.seconds_burn, unburned));
}

/// The ET range, and a warning when some vertices have ET < 0.
void report_et(const EtRun& run, const MedialComplex& medial, Context& ctx) {
  const auto& et = medial.get(kEt);
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
  for (const Segment& e : run.complex.edges)
    steep += std::abs(medial.radii[e[0]] - medial.radii[e[1]]) > (medial.centres[e[0]] - medial.centres[e[1]]).norm();
  ctx.info(fmt::format("et in [{:g}, {:g}]; {} vertices with et = inf; {} edges where |dR| > length", lo, hi, infinite,
                       steep));
  if (negative > 0)
    ctx.warn(fmt::format("{} of {} vertices ({:.2f}%, lowest ET {:g}) have ET < 0: the interpolated radius varies "
                         "faster than distance along some arcs ({} edges, and arcs across skinny triangles; the "
                         "paper's g > 1), so fire reaches them before their own ignition time",
                         negative, et.size(), 100.0 * negative / std::max<std::size_t>(1, et.size()), lo, steep));
}

/// `<id>_burn_forest.obj`: the graph's nodes and one line per primary arc.
void write_burn_forest(const std::shared_ptr<const EtRun>& run, Context& ctx) {
  ctx.write_output(ctx.stage_id() + "_burn_forest.obj", [run](std::ostream& out) {
    const BurnGraph& g = run->graph;
    out << "# medax erosion_thickness: burn forest (one line per primary arc)\n";
    for (const Vec3& p : g.pos) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (Index n = 0; n < g.num_nodes(); ++n)
      for (Index s = g.sector_begin[n]; s < g.sector_begin[n + 1]; ++s)
        if (run->burn.prime_node[s] != kNone) out << "l " << run->burn.prime_node[s] + 1 << ' ' << n + 1 << '\n';
  });
}

}  // namespace

void ErosionThicknessStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  if (medial.faces.empty()) ctx.warn("the complex has no triangles: every vertex is its own boundary (ET = 0)");
  const double L = reference_length(shape, medial, options_.relative_to);
  const double omega = options_.omega * L;
  const std::shared_ptr<const EtRun> run = run_erosion_thickness(medial, omega, options_.min_samples, canceller(ctx));
  log_burn(*run, omega, L, ctx);
  store_erosion_thickness(*run, medial);
  report_et(*run, medial, ctx);
  if (write_forest_) write_burn_forest(run, ctx);
  ctx.publish(kBurnData, SharedBurn{run, options_, L, fingerprint(medial)});
}

// ---- local measures ------------------------------------------------------------------------

namespace {

const Property<double> kRadius{Element::Vertex, "medial_radius", 1};
const Property<double> kObjectAngle{Element::Vertex, "object_angle"};
const Property<double> kCircumradius{Element::Vertex, "circumradius", 1};

/// Adds vertex field `p` and the face field of the same name (the mean of its corners).
void add_with_face_mean(MedialComplex& medial, const Property<double>& p, const std::vector<double>& values) {
  medial.add(p) = values;
  auto& f = medial.add(Property<double>{Element::Face, p.name, p.length_power});
  for (std::size_t i = 0; i < medial.faces.size(); ++i)
    f[i] = (values[medial.faces[i][0]] + values[medial.faces[i][1]] + values[medial.faces[i][2]]) / 3;
}

}  // namespace

StageInfo RadiusMeasureStage::describe() {
  return {"radius_measure", "The medial radius R as a significance field `medial_radius` (vertex; face mean)", kDoc};
}

void RadiusMeasureStage::measure(const Shape&, MedialComplex& medial, Context& ctx) {
  add_with_face_mean(medial, kRadius, medial.radii);
  ctx.info(fmt::format("radius on {} vertices", medial.num_vertices()));
}

void GeneratorMeasureStage::declare(ParamBinder& p) {
  p.add("tolerance", tolerance_,
        "Without generators: surface points within (1 + tolerance) x the nearest distance count as generators")
      .at_least(0)
      .in_unit("ratio");
}

StageInfo ObjectAngleStage::describe() {
  return {"object_angle",
          "Object angle: largest angle at the centre between two generators, field `object_angle` (radians)", kDoc};
}

void ObjectAngleStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  std::string source;
  const auto gens = medial_generators(shape, medial, tolerance_, &source);
  std::vector<double> angle(medial.num_vertices());
  std::size_t single = 0;
  for (std::size_t v = 0; v < angle.size(); ++v) {
    angle[v] = max_pairwise_angle(medial.centres[v], gens[v]);
    single += gens[v].size() < 2;
  }
  add_with_face_mean(medial, kObjectAngle, angle);
  ctx.info(fmt::format("object angle from {}; {} vertices with fewer than 2 generators (angle 0)", source, single));
}

StageInfo CircumradiusStage::describe() {
  return {"circumradius",
          "Circumradius of the generators (the lambda of the lambda-medial axis), field `circumradius`", kDoc};
}

void CircumradiusStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  std::string source;
  const auto gens = medial_generators(shape, medial, tolerance_, &source);
  std::vector<double> lambda(medial.num_vertices());
  for (std::size_t v = 0; v < lambda.size(); ++v) lambda[v] = std::max(0.0, min_enclosing_ball(gens[v]).radius);
  add_with_face_mean(medial, kCircumradius, lambda);
  ctx.info(fmt::format("circumradius from {}", source));
}

// ---- et_medial_curves ----------------------------------------------------------------------

StageInfo MedialCurvesStage::describe() {
  return {"et_medial_curves",
          "Medial curves dual to the burn trees (Yan et al. 2016, §7), with ET_C, from the burn of erosion_thickness; "
          "replaces the complex by the curves",
          kDoc};
}

void MedialCurvesStage::check_scene(const Scene& scene) const { burn_of(scene.data, *scene.medial); }

void MedialCurvesStage::connect(const Shape&, MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology before = services::complex_topology(medial);
  const SharedBurn& burn = burn_of(ctx.data(), medial);
  const EtRun& run = *burn.run;
  log_burn_use(ctx.data(), burn, ctx);
  if (!run.loose_edges.empty())
    ctx.warn(fmt::format("{} edges bound no triangle and are left out of the curves; run `pure_complex` first",
                         run.loose_edges.size()));
  const Subdivision sub = build_subdivision(run.graph, run.burn);
  const MedialCurves curves = extract_medial_curves(run.graph, sub);
  ctx.info(fmt::format("subdivision: {} faces, {} curve edges, {} bridges; {} closed-surface triangles kept",
                       sub.num_faces(), sub.curve_edges.size(), sub.bridges, sub.residue_triangles));
  if (sub.crossing_arcs > 0)
    ctx.warn(fmt::format("{} burn arcs crossed another in their triangle (round-off) and were left out: the "
                         "curves may not be homotopy equivalent to the complex",
                         sub.crossing_arcs));
  store_medial_curves(curves, medial);
  record_replacement(medial, ctx);
  const services::ComplexTopology after = services::complex_topology(medial);
  ctx.info("complex: " + topology_text(before) + "; curves: " + topology_text(after));
  if (run.loose_edges.empty() && !same_topology(before, after))
    ctx.warn("the curves' topology differs from the complex's (see the line above)");
}

// ---- et_skeleton ---------------------------------------------------------------------------

StageInfo EtSkeletonStage::describe() {
  return {"et_skeleton",
          "Topology-preserving skeleton of sheets (ET > theta2) and curves (ET_C > theta1) (Yan et al. 2016, §7.3), "
          "from the burn of erosion_thickness",
          kDoc};
}

void EtSkeletonStage::declare(ParamBinder& p) {
  p.add("theta2", options_.theta2,
        "Sheets whose ET exceeds theta2 x L are kept (L: the burn's reference length; paper: 0.01-0.03; .inf keeps "
        "none)")
      .at_least(0)
      .in_unit("fraction of reference length");
  p.add("theta1", options_.theta1,
        "Curves whose ET_C exceeds theta1 x L are kept (paper: 0.02-0.06; .inf keeps none)")
      .at_least(0)
      .in_unit("fraction of reference length");
  p.add("phi2", options_.phi2, "Kept sheet components of area below phi2 x L^2 are dropped")
      .at_least(0)
      .in_unit("fraction of reference area");
  p.add("phi1", options_.phi1, "Kept curve components of length below phi1 x L are dropped")
      .at_least(0)
      .in_unit("fraction of reference length");
}

void EtSkeletonStage::check_scene(const Scene& scene) const { burn_of(scene.data, *scene.medial); }

void EtSkeletonStage::simplify(const Shape&, MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology before = services::complex_topology(medial);
  const SharedBurn& burn = burn_of(ctx.data(), medial);
  const EtRun& run = *burn.run;
  log_burn_use(ctx.data(), burn, ctx);
  const Subdivision sub = build_subdivision(run.graph, run.burn);
  if (sub.crossing_arcs > 0)
    ctx.warn(fmt::format("{} burn arcs crossed another in their triangle (round-off) and were left out",
                         sub.crossing_arcs));
  const double L = burn.length;
  SkeletonOptions o = options_;
  o.theta2 = options_.theta2 * L;
  o.theta1 = options_.theta1 * L;
  o.phi2 = options_.phi2 * L * L;
  o.phi1 = options_.phi1 * L;
  const Skeleton sk = compute_skeleton(run.graph, sub, run.loose_edges, o);
  ctx.info(fmt::format("refined cell complex: {} points, {} 1-cells, {} wedges; protected {} wedges, {} curve "
                       "cells ({} sheet and {} curve components below the size limits dropped); {:.3f} s to build, "
                       "{:.3f} s to contract; {} input triangles written whole",
                       sk.refined_vertices, sk.refined_edges, sk.refined_faces, sk.protected_faces,
                       sk.protected_curve_edges, sk.dropped_sheet_components, sk.dropped_curve_components,
                       sk.seconds_refine, sk.seconds_contract, sk.coarse_triangles));
  store_skeleton(sk, medial);
  record_replacement(medial, ctx);
  const services::ComplexTopology after = services::complex_topology(medial);
  ctx.info("input: " + topology_text(before) + "; skeleton: " + topology_text(after));
  if (!same_topology(before, after)) ctx.warn("the skeleton's topology differs from the input's (see the line above)");
}

// ---- pure_complex --------------------------------------------------------------------------

StageInfo PureComplexStage::describe() {
  return {"pure_complex",
          "Clean a medial complex into a pure 2-complex: weld, drop degenerate/duplicate triangles, dangling "
          "edges and isolated vertices",
          kDoc};
}

void PureComplexStage::declare(ParamBinder& p) {
  p.add("weld_tolerance", weld_tolerance_,
        "Centres closer than this fraction of the complex's longest bbox side are welded (0: only identical "
        "centres; Voronoi vertices of cospherical points differ by round-off)")
      .range(0, 0.1)
      .in_unit("fraction of complex max side");
}

void PureComplexStage::simplify(const Shape&, MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology before = services::complex_topology(medial);
  double side = 0;
  if (!medial.centres.empty()) {
    Vec3 lo = medial.centres[0], hi = lo;
    for (const Vec3& p : medial.centres) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    side = (hi - lo).maxCoeff();
  }
  const PureComplexReport r = make_pure_complex(medial, weld_tolerance_ * side);
  record_replacement(medial, ctx);
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
