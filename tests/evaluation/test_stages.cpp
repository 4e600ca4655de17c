// The evaluation package: reconstruction metrics on shapes whose envelope distance is known,
// counts on a hand-built complex, topology, and the package loaded and run in a pipeline.
#include "pipeline_run.hpp"
#include "counts.hpp"
#include "reconstruction.hpp"
#include "stages.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>
#include <medax/plugin.hpp>
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>
#include <capturing_context.hpp>
#include "shape_fixtures.hpp"
#include <test_paths.hpp>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <thread>

using namespace medax;

namespace {

using test::icosphere_sag;
using test::one_sphere;

/// Runs a fresh stage at its defaults with `changes` applied.
Metrics run_stage(EvaluationStage& stage, const Shape& shape, const MedialComplex& mc,
                  const std::map<std::string, ParamValue>& changes = {}, std::uint64_t seed = 1) {
  ParamSet params;
  for (const auto& [name, value] : changes) params.set(name, value);
  stage.configure(params);
  BasicContext ctx(seed);
  return stage.evaluate(shape, mc, ctx);
}

Metrics reconstruction(const Shape& shape, const MedialComplex& mc, const std::map<std::string, ParamValue>& changes = {},
                       std::uint64_t seed = 1) {
  evaluation::ReconstructionStage stage;
  return run_stage(stage, shape, mc, changes, seed);
}

}  // namespace

TEST_CASE("reconstruction: a sphere against the one-vertex complex of the same radius: only the tessellation error", "[reconstruction]") {
  Shape shape;
  shape.mesh = testing::make_sphere(1.0, 5);
  const double sag = icosphere_sag(shape.mesh, 1.0);
  const Metrics m = reconstruction(shape, one_sphere(1.0));
  INFO("sag " << sag << ", hausdorff " << m.at("hausdorff"));
  // The mesh vertices lie on the sphere: surface → envelope is zero.
  CHECK(m.at("surface_to_envelope_max") < 1e-12);
  CHECK(m.at("eps1") < 1e-12);
  // The envelope → mesh distances are the tessellation's sag, nothing more.
  CHECK(m.at("envelope_to_surface_max") <= sag + 1e-9);
  CHECK(m.at("envelope_to_surface_max") >= 0.5 * sag);
  CHECK(m.at("eps2") < sag);
  CHECK(m.at("hausdorff_pct") == Approx(100 * m.at("hausdorff") / m.at("bbox_diagonal")));
  CHECK(m.at("hausdorff_pct") < 0.01);
  CHECK(m.at("eps") == Approx(std::max(m.at("eps1"), m.at("eps2"))));
  CHECK(m.at("envelope_area") == Approx(4 * M_PI).epsilon(0.005));
  CHECK(m.at("envelope_primitives") == 1);
  CHECK(m.at("surface_samples") == shape.mesh.vertices.size());
}

TEST_CASE("reconstruction: a sphere of radius R against the one-vertex complex of radius R' gives |R - R'| both ways", "[reconstruction]") {
  Shape shape;
  shape.mesh = testing::make_sphere(1.0, 5);
  const double sag = icosphere_sag(shape.mesh, 1.0);
  for (const double r : {0.8, 1.25}) {
    const Metrics m = reconstruction(shape, one_sphere(r));
    const double gap = std::abs(1.0 - r);
    const double step = m.at("envelope_step");
    INFO("R' = " << r << ", step " << step);
    // Outside the envelope (R' < R) the distance is exact; inside (R' > R) it is the distance to
    // the nearest boundary point, within a fraction of the step.
    const double tol_s2e = r < 1 ? 1e-12 : step * step / gap;
    CHECK(m.at("surface_to_envelope_max") == Approx(gap).margin(tol_s2e));
    CHECK(m.at("surface_to_envelope_mean") == Approx(gap).margin(tol_s2e));
    CHECK(m.at("surface_to_envelope_mean") >= gap - 1e-12);
    CHECK(m.at("surface_inside_fraction") == (r > 1 ? 1.0 : 0.0));
    // The envelope is the exact sphere R': its distance to the mesh is |R − R'| up to the sag.
    CHECK(m.at("envelope_to_surface_max") == Approx(gap).margin(sag + 1e-9));
    CHECK(m.at("envelope_to_surface_mean") == Approx(gap).margin(sag + 1e-9));
    CHECK(m.at("hausdorff") == Approx(gap).margin(sag + tol_s2e));
    CHECK(m.at("eps") == Approx(gap).margin(sag + tol_s2e));
    CHECK(m.at("envelope_area") == Approx(4 * M_PI * r * r).epsilon(0.005));
  }
}

TEST_CASE("reconstruction: a capsule against its two spheres and cone gives the tessellation error only", "[reconstruction]") {
  const double radius = 0.3, half = 0.7;
  Shape shape;
  shape.mesh = testing::make_capsule(radius, half, 128);
  // How far the mesh strays inside the exact capsule, measured at face centroids (the deepest
  // point of a flat triangle under a convex surface, up to second order).
  double sag = 0;
  for (const Tri& f : shape.mesh.faces) {
    const Vec3 g = (shape.mesh.vertices[f[0]] + shape.mesh.vertices[f[1]] + shape.mesh.vertices[f[2]]) / 3.0;
    sag = std::max(sag, radius - testing::capsule_axis_distance(g, half));
  }
  MedialComplex mc;
  mc.add_vertex({0, 0, -half}, radius);
  mc.add_vertex({0, 0, half}, radius);
  mc.add_edge(0, 1);
  const Metrics m = reconstruction(shape, mc);
  INFO("sag " << sag << ", hausdorff " << m.at("hausdorff"));
  CHECK(m.at("surface_to_envelope_max") < 1e-12);
  CHECK(m.at("envelope_to_surface_max") <= 1.5 * sag);
  CHECK(m.at("hausdorff_pct") < 100 * 1.5 * sag / m.at("bbox_diagonal"));
  CHECK(m.at("envelope_area") == Approx(4 * M_PI * radius * radius + 4 * M_PI * radius * half).epsilon(0.005));

  SECTION("the same envelope split into a chain of spheres and cones measures the same") {
    MedialComplex chain;
    for (int i = 0; i <= 10; ++i) chain.add_vertex({0, 0, -half + 2 * half * i / 10.0}, radius);
    for (Index i = 0; i < 10; ++i) chain.add_edge(i, i + 1);
    const Metrics c = reconstruction(shape, chain);
    CHECK(c.at("hausdorff") == Approx(m.at("hausdorff")).margin(1e-9));
    CHECK(c.at("eps2") == Approx(m.at("eps2")).margin(1e-9));
  }
}

namespace {

/// A capsule (radius 0.3, half-length 0.7) and half its axis: the far hemisphere is uncovered.
struct HalfCoveredCapsule {
  double radius = 0.3, half = 0.7;
  Shape shape;
  MedialComplex mc;
  HalfCoveredCapsule() {
    shape.mesh = testing::make_capsule(radius, half, 96);
    mc.add_vertex({0, 0, -half}, radius);
    mc.add_vertex({0, 0, 0}, radius);
    mc.add_edge(0, 1);
  }
};

}  // namespace

TEST_CASE("reconstruction: a complex that misses part of the shape: surface to envelope sees it", "[reconstruction]") {
  const HalfCoveredCapsule capsule;
  const double radius = capsule.radius, half = capsule.half;
  const Shape& shape = capsule.shape;
  const MedialComplex& mc = capsule.mc;
  const Metrics m = reconstruction(shape, mc);
  // The top pole is at distance half from the envelope's top.
  CHECK(m.at("surface_to_envelope_max") == Approx(half).margin(1e-9));
  // The top of the envelope, (0, 0, radius), is `radius` from the capsule wall; the samples miss
  // it by at most their covering radius (below a step).
  CHECK(m.at("envelope_to_surface_max") <= radius + 1e-9);
  CHECK(m.at("envelope_to_surface_max") >= radius - m.at("envelope_step"));
  CHECK(m.at("hausdorff") == Approx(half).margin(1e-9));
}

TEST_CASE("reconstruction: the default point budget enlarges a slender shape's step; 0 keeps the VMAS rule",
          "[reconstruction]") {
  // The capsule and half-axis complex above: surface → envelope is exact at any step, envelope →
  // surface within the samples' covering radius (below a step).
  const HalfCoveredCapsule capsule;
  const double radius = capsule.radius, half = capsule.half;
  const Shape& shape = capsule.shape;
  const MedialComplex& mc = capsule.mc;
  // resolution 40: the VMAS rule's step is 0.6 / 40, which would give about 1.5 × area / step²
  // ≈ 25,000 points on the capsule's surface, more than the default budget.
  const Metrics vmas = reconstruction(shape, mc, {{"resolution", 40LL}, {"max_envelope_samples", 0LL}});
  const Metrics budget = reconstruction(shape, mc, {{"resolution", 40LL}});
  const double area = services::surface_area(shape.mesh);
  const double allowed = static_cast<double>(evaluation::ReconstructionOptions{}.max_envelope_samples);
  REQUIRE(1.5 * area / (0.015 * 0.015) > allowed);
  CHECK(vmas.at("envelope_step") == Approx(0.6 / 40));
  CHECK(budget.at("envelope_step") == Approx(std::sqrt(1.5 * area / allowed)));
  CHECK(budget.at("envelope_samples") < vmas.at("envelope_samples"));
  // About 1.5 points per step² of ∂E (here half the capsule: the budget is on the surface's area).
  const double step = budget.at("envelope_step");
  CHECK(budget.at("envelope_samples") == Approx(1.5 * budget.at("envelope_area") / (step * step)).epsilon(0.1));
  CHECK(budget.at("envelope_samples") <= allowed);
  // The same metrics on one thread (a deterministic sampling and refinement).
  Metrics one_thread;
  tbb::task_arena(1).execute([&] { one_thread = reconstruction(shape, mc, {{"resolution", 40LL}}); });
  CHECK(one_thread == budget);
  for (const Metrics* m : {&vmas, &budget}) {
    CHECK(m->at("surface_to_envelope_max") == Approx(half).margin(1e-9));
    CHECK(m->at("envelope_to_surface_max") <= radius + 1e-9);
    CHECK(m->at("envelope_to_surface_max") >= radius - m->at("envelope_step"));
  }
}

TEST_CASE("reconstruction: options: uniform surface samples, seeding, point clouds, steps", "[reconstruction]") {
  Shape shape;
  shape.mesh = testing::make_sphere(1.0, 4);
  const MedialComplex mc = one_sphere(0.9);
  SECTION("uniform samples add to the vertices and are seeded") {
    const Metrics a = reconstruction(shape, mc, {{"surface_samples", 5000LL}}, 3);
    const Metrics b = reconstruction(shape, mc, {{"surface_samples", 5000LL}}, 3);
    CHECK(a.at("surface_samples") == shape.mesh.vertices.size() + 5000);
    CHECK(a == b);
    // Samples inside faces are closer to the centre than the vertices: at most 0.1, at least 0.1 − sag.
    CHECK(a.at("surface_to_envelope_max") == Approx(0.1).margin(1e-12));
    CHECK(a.at("surface_to_envelope_mean") < 0.1);
  }
  SECTION("only uniform samples") {
    const Metrics a = reconstruction(shape, mc, {{"vertices", false}, {"surface_samples", 2000LL}});
    CHECK(a.at("surface_samples") == 2000);
  }
  SECTION("a point cloud without a mesh") {
    Shape cloud;
    cloud.samples = services::vertex_samples(shape.mesh);
    const Metrics a = reconstruction(cloud, mc);
    CHECK(a.at("surface_to_envelope_max") == Approx(0.1).margin(1e-12));
    CHECK(a.at("envelope_to_surface_max") >= 0.1 - 1e-9);
  }
  SECTION("a thin plate: the point budget enlarges the step, an explicit step is kept") {
    Shape plate;
    plate.mesh = testing::make_box(1.0, 1.0, 0.001, 4);  // smallest side 0.002: step 1.3e-5
    MedialComplex mid;
    mid.add_vertex(Vec3::Zero(), 0.001);
    const Metrics a = reconstruction(plate, mid, {{"max_envelope_samples", 20000LL}});
    CHECK(a.at("envelope_step") == Approx(std::sqrt(1.5 * 8.016 / 20000)).epsilon(1e-6));
    const Metrics b = reconstruction(plate, mid, {{"max_envelope_samples", 20000LL}, {"step", 0.0002}});
    CHECK(b.at("envelope_step") == 0.0002);
  }
  SECTION("an absolute step overrides the resolution") {
    const Metrics a = reconstruction(shape, mc, {{"step", 0.05}});
    CHECK(a.at("envelope_step") == 0.05);
    const Metrics b = reconstruction(shape, mc, {{"resolution", 40LL}});
    CHECK(b.at("envelope_step") == Approx(1.8 / 40));  // the envelope's side is the smaller
  }
}

TEST_CASE("reconstruction: a point cloud on a sphere against its exact medial sphere, both ways", "[reconstruction]") {
  // Oriented samples and no mesh: the icosphere's vertices, on the unit sphere.
  const SurfaceMesh ico = testing::make_sphere(1.0, 3);
  Shape cloud;
  cloud.samples = services::vertex_samples(ico);
  REQUIRE(cloud.mesh.empty());
  // The farthest point of the sphere from the samples is a spherical Voronoi vertex: the unit
  // normal of a face of their convex hull (the icosphere), equidistant from its three corners.
  double covering = 0;
  for (const Tri& f : ico.faces) {
    const Vec3 n = (ico.vertices[f[1]] - ico.vertices[f[0]]).cross(ico.vertices[f[2]] - ico.vertices[f[0]]).normalized();
    covering = std::max(covering, (n - ico.vertices[f[0]]).norm());
  }
  const Metrics m = reconstruction(cloud, one_sphere(1.0));
  const double step = m.at("envelope_step");
  INFO("covering radius " << covering << ", step " << step);
  // Samples → envelope: they lie on ∂E.
  CHECK(m.at("surface_to_envelope_max") < 1e-12);
  CHECK(m.at("eps1") < 1e-12);
  // Envelope → samples: ∂E is the unit sphere, whose farthest point from the samples is at the
  // covering radius; the boundary points come within the grid's covering radius (< a step) of it.
  CHECK(m.at("envelope_to_surface_max") <= covering + 1e-9);
  CHECK(m.at("envelope_to_surface_max") >= covering - step);
  CHECK(m.at("envelope_to_surface_mean") < covering);
  CHECK(m.at("envelope_to_surface_mean") > 0.25 * covering);
  CHECK(m.at("hausdorff") == m.at("envelope_to_surface_max"));
  CHECK(m.at("eps") == m.at("eps2"));
  CHECK(m.at("surface_samples") == ico.vertices.size());
  CHECK(m.at("envelope_area") == Approx(4 * M_PI).epsilon(0.005));
}

TEST_CASE("reconstruction: the same metrics on 1 and 2 threads", "[reconstruction]") {
  // A ring of cones and a band of slabs inside a torus: parallel loops over many primitives.
  Shape shape;
  shape.mesh = testing::make_torus(1.0, 0.3, 48, 16);
  MedialComplex mc;
  for (int i = 0; i < 24; ++i) {
    const double a = i * M_PI / 12;
    mc.add_vertex(Vec3(std::cos(a), std::sin(a), 0), 0.25 + 0.03 * std::sin(3 * a));
    mc.add_vertex(Vec3(1.1 * std::cos(a), 1.1 * std::sin(a), 0.05), 0.18);
  }
  for (Index i = 0; i < 24; ++i) {
    const Index j = (i + 1) % 24;
    mc.add_edge(2 * i, 2 * j);
    if (i % 2 == 0) mc.add_face(2 * i + 1, 2 * j + 1, 2 * j);
  }
  const auto on_threads = [&](int threads) {
    Metrics m;
    tbb::task_arena(threads).execute([&] { m = reconstruction(shape, mc, {{"surface_samples", 3000LL}}); });
    return m;
  };
  const Metrics one = on_threads(1), two = on_threads(2);
  CHECK(one.at("envelope_samples") > 1000);
  CHECK(one == two);  // every value bit for bit
}

TEST_CASE("reconstruction: export_envelope writes the boundary points in the input's frame", "[reconstruction]") {
  Shape shape;
  shape.mesh = testing::make_sphere(1.0, 3);
  shape.to_input = Similarity{2.0, Vec3(1, 0, 0)};  // the input was twice as big, shifted
  evaluation::ReconstructionStage stage;
  ParamSet params;
  params.set("export_envelope", true);
  params.set("resolution", 30LL);
  stage.configure(params);
  stage.set_id("recon");
  test::CapturingContext ctx;
  const Metrics m = stage.evaluate(shape, one_sphere(0.5), ctx);
  REQUIRE(ctx.files.count("recon_envelope.ply") == 1);
  std::istringstream in(ctx.files["recon_envelope.ply"]);
  std::string line;
  std::size_t count = 0;
  std::vector<std::string> properties;
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("element vertex ", 0) == 0) count = std::stoul(line.substr(15));
    if (line.rfind("property double ", 0) == 0) properties.push_back(line.substr(16));
  }
  CHECK(properties == std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "area", "distance"});
  CHECK(count == m.at("envelope_samples"));
  // The same measurement, to compare the values read back with: they are exact (the writer
  // prints the shortest form that reads back to the same double).
  evaluation::ReconstructionOptions options;
  options.resolution = 30;
  std::mt19937_64 rng(0);
  const evaluation::ReconstructionResult r = evaluation::measure_reconstruction(shape, one_sphere(0.5), options, rng);
  REQUIRE(r.envelope.size() == count);
  std::size_t rows = 0, exact = 0;
  double x, y, z, nx, ny, nz, area, distance;
  while (in >> x >> y >> z >> nx >> ny >> nz >> area >> distance) {
    CHECK((Vec3(x, y, z) - Vec3(1, 0, 0)).norm() == Approx(2 * 0.5).margin(1e-9));  // radius 0.5, scaled
    CHECK(distance == Approx(2 * 0.5).margin(2 * icosphere_sag(shape.mesh, 1.0) + 1e-9));
    if (rows < count && Vec3(x, y, z) == shape.to_input.apply(r.envelope.points[rows]) &&
        Vec3(nx, ny, nz) == r.envelope.normals[rows] && area == r.envelope.areas[rows] * 4.0 &&
        distance == 2.0 * r.envelope_distances[rows])
      ++exact;
    ++rows;
  }
  CHECK(rows == count);
  CHECK(exact == count);
}

TEST_CASE("reconstruction: refuses what it cannot measure", "[reconstruction]") {
  evaluation::ReconstructionStage stage;
  ParamSet params;
  params.set("vertices", false);
  stage.configure(params);
  CHECK_THROWS_WITH(stage.check_params(), Catch::Contains("surface_samples"));
  Scene scene;
  scene.shape.mesh = testing::make_sphere(1.0, 1);
  CHECK_THROWS_AS(stage.prepare(scene), std::invalid_argument);  // no medial complex
  scene.medial = MedialComplex{};
  CHECK_THROWS_WITH(stage.prepare(scene), Catch::Contains("empty"));
  scene.medial = one_sphere(1.0);
  CHECK_NOTHROW(stage.prepare(scene));
  params.set("vertices", true);
  stage.configure(params);
  CHECK_NOTHROW(stage.check_params());
  Scene nothing;
  nothing.medial = one_sphere(1.0);
  CHECK_THROWS_WITH(stage.prepare(nothing), Catch::Contains("neither a mesh nor samples") &&
                                                !Catch::Contains("reconstruction:"));
}

TEST_CASE("evaluation stages: a fresh stage runs at the declared defaults, which are the algorithm's",
          "[reconstruction][topology]") {
  std::map<std::string, ParamSpec> specs;
  for (const ParamSpec& p : stage_info<evaluation::ReconstructionStage>().params) specs[p.name] = p;
  const evaluation::ReconstructionOptions defaults;
  CHECK(std::get<long long>(specs.at("resolution").default_value) == defaults.resolution);
  CHECK(std::get<double>(specs.at("step").default_value) == defaults.step);
  CHECK(std::get<bool>(specs.at("vertices").default_value) == defaults.use_vertices);
  CHECK(std::get<long long>(specs.at("surface_samples").default_value) == static_cast<long long>(defaults.uniform_samples));
  CHECK(std::get<long long>(specs.at("max_envelope_samples").default_value) ==
        static_cast<long long>(defaults.max_envelope_samples));
  CHECK(std::get<bool>(specs.at("export_envelope").default_value) == false);
  CHECK(specs.size() == 6);
  CHECK(stage_info<evaluation::CountsStage>().params.empty());
  const std::vector<ParamSpec> topology = stage_info<evaluation::TopologyStage>().params;
  REQUIRE(topology.size() == 1);
  CHECK(topology[0].name == "input");
  CHECK(topology[0].default_text() == "true");
}

TEST_CASE("counts: a small hand-built complex", "[counts]") {
  MedialComplex mc;
  for (int v = 0; v < 8; ++v) mc.add_vertex(Vec3(v, v % 2, 0), 0.1);
  mc.add_face(0, 1, 2);
  mc.add_face(1, 2, 3);
  mc.add_face(2, 1, 0);  // duplicate of the first
  mc.add_edge(0, 1);     // a triangle side: not a unique edge
  mc.add_edge(3, 4);     // unique
  mc.add_edge(4, 4);     // degenerate: ignored
  mc.add_face(4, 5, 5);  // degenerate triangle: the unique edge 4-5
  mc.add_edge(5, 6);     // unique; vertex 7 stays isolated
  evaluation::CountsStage stage;
  const Metrics m = run_stage(stage, Shape{}, mc);
  CHECK(m.at("vertices") == 8);
  CHECK(m.at("faces") == 2);
  CHECK(m.at("unique_edges") == 3);
  CHECK(m.at("edges") == 8);  // 5 triangle sides + 3 unique
  CHECK(m.at("isolated_vertices") == 1);
  CHECK(m.at("N_d") == 8 + 3 + 2);
  CHECK(m.at("N_c") == 4 * 8);
}

TEST_CASE("topology stage: a ring complex inside a torus", "[topology]") {
  Shape shape;
  shape.mesh = testing::make_torus(1.0, 0.3, 48, 16);
  MedialComplex ring;
  for (int i = 0; i < 12; ++i) ring.add_vertex(Vec3(std::cos(i * M_PI / 6), std::sin(i * M_PI / 6), 0), 0.3);
  for (Index i = 0; i < 12; ++i) ring.add_edge(i, (i + 1) % 12);
  evaluation::TopologyStage stage;
  const Metrics m = run_stage(stage, shape, ring);
  CHECK(m.at("components") == 1);
  CHECK(m.at("euler") == 0);
  CHECK(m.at("b0") == 1);
  CHECK(m.at("b1") == 1);
  CHECK(m.at("b2") == 0);
  CHECK(m.at("input_components") == 1);
  CHECK(m.at("input_euler") == 0);
  CHECK(m.at("input_genus") == 1);
  CHECK(m.at("input_b1") == 2);
  CHECK(m.at("input_closed") == 1);
  evaluation::TopologyStage without_input;
  const Metrics without = run_stage(without_input, shape, ring, {{"input", false}});
  CHECK(without.count("input_genus") == 0);
}

TEST_CASE("evaluation: the evaluation package loads and runs in a pipeline", "[pipeline]") {
  Registry registry;
  REQUIRE(registry.load_file(MEDAX_EVALUATION_PLUGIN));
  for (const char* name : {"reconstruction", "counts", "topology"}) {
    const RegisteredStage* stage = registry.find(name);
    REQUIRE(stage);
    CHECK(stage->info().role == Role::Evaluation);
    CHECK(stage->info().doc == "docs/plugins/evaluation.md");
  }
  const auto dir = test::scratch_dir("evaluation_pipeline");
  write_mesh(dir / "sphere.off", testing::make_sphere(2.0, 4));
  MedialComplex mc = one_sphere(1.5);
  write_medial(dir / "sphere.ma", mc);
  const RunResult result = test::run_yaml_text(dir,
                                               "name: evaluation\nseed: 0\ninput: sphere.off\nmedial_input: sphere.ma\n"
                                               "stages:\n"
                                               "  - plugin: reconstruction\n    params: {surface_samples: 1000}\n"
                                               "  - plugin: counts\n"
                                               "  - plugin: topology\n"
                                               "outputs: {medial: [ma]}\n",
                                               registry);
  INFO(result.error);
  REQUIRE(result.ok);
  std::ifstream in(dir / "run" / "metrics.json");
  const nlohmann::json metrics = nlohmann::json::parse(in);
  CHECK(metrics["reconstruction"]["surface_to_envelope_max"].get<double>() == Approx(0.5).margin(1e-12));
  CHECK(metrics["reconstruction"]["hausdorff"].get<double>() == Approx(0.5).margin(0.01));
  CHECK(metrics["counts"]["N_c"].get<double>() == 4);
  CHECK(metrics["topology"]["b0"].get<double>() == 1);
  CHECK(metrics["topology"]["input_genus"].get<double>() == 0);
}

namespace {

/// A context that says "cancelled" from its `cancel_at`-th poll on (polls are counted from
/// every thread), and counts the polls made after that: each is a stop that was not acted on.
class CancelAtPoll : public BasicContext {
 public:
  explicit CancelAtPoll(long cancel_at) : cancel_at_(cancel_at) {}
  bool cancelled() const override { return polls_.fetch_add(1) + 1 >= cancel_at_; }
  /// Polls answered "cancelled" beyond the first.
  long ignored_stops() const { return std::max(0L, polls_.load() - cancel_at_); }

 private:
  long cancel_at_;
  mutable std::atomic<long> polls_{0};
};

/// A context cancelled by another thread.
class FlagContext : public BasicContext {
 public:
  bool cancelled() const override { return flag.load(); }
  std::atomic<bool> flag{false};
};

}  // namespace

TEST_CASE("reconstruction: a cancel stops the envelope loops within a few hundred work items",
          "[reconstruction][cancel]") {
  // A fine grid on a sphere: about 750k envelope points, thousands of polls (one per 256 items).
  Shape sphere;
  sphere.mesh = testing::make_sphere(1.0, 4);
  const MedialComplex mc = one_sphere(1.0);
  evaluation::ReconstructionStage stage;
  ParamSet params;
  params.set("resolution", ParamValue(400LL));
  params.set("max_envelope_samples", ParamValue(0LL));  // no budget: the fine grid
  stage.configure(params);
  for (long cancel_at : {1L, 10L, 100L, 1000L, 3000L}) {
    CancelAtPoll ctx(cancel_at);
    INFO("cancelled at poll " << cancel_at);
    CHECK_THROWS_AS(stage.evaluate(sphere, mc, ctx), Cancelled);
    // Every thread sees the stop at its next poll: a few more polls per thread (≤ 256 work items
    // each), never the thousands left of the run.
    CHECK(ctx.ignored_stops() <= 4L * tbb::this_task_arena::max_concurrency() + 16);
  }
}

TEST_CASE("reconstruction: a cancel from another thread ends the stage promptly", "[reconstruction][cancel]") {
  Shape sphere;
  sphere.mesh = testing::make_sphere(1.0, 4);
  const MedialComplex mc = one_sphere(1.0);
  evaluation::ReconstructionStage stage;
  ParamSet params;
  params.set("resolution", ParamValue(1000LL));  // tens of seconds uncancelled
  params.set("max_envelope_samples", ParamValue(0LL));
  stage.configure(params);
  FlagContext ctx;
  std::chrono::steady_clock::time_point cancelled_at;
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    cancelled_at = std::chrono::steady_clock::now();
    ctx.flag = true;
  });
  CHECK_THROWS_AS(stage.evaluate(sphere, mc, ctx), Cancelled);
  const auto stopped_at = std::chrono::steady_clock::now();
  canceller.join();
  // A generous bound (a loaded machine): before, a stop could take seconds at this size.
  CHECK(std::chrono::duration<double>(stopped_at - cancelled_at).count() < 2.0);
}
