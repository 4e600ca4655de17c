// The erosion_thickness package's stages called directly (fields, parameters, the clean-up, the
// local measures) and through a pipeline with the built plugin.
#include "pipeline_run.hpp"
#include "erosion_thickness.hpp"
#include "fixtures.hpp"
#include "local_measures.hpp"
#include "pure_complex.hpp"
#include "stages.hpp"
#include "voronoi_fixture.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>
#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

using namespace medax;
using namespace medax::et;
namespace fx = medax::et::testing;

namespace {

template <typename StageT>
StageT configured(std::initializer_list<std::pair<const char*, ParamValue>> overrides = {}) {
  StageT stage;
  ParamSet params = default_params(StageT::describe().params);
  for (const auto& [name, value] : overrides) params.set(name, value);
  stage.configure(params);
  return stage;
}

Shape box_shape(double half) {
  Shape shape;
  shape.mesh = medax::testing::make_box(half, half, half, 1);
  return shape;
}

}  // namespace

TEST_CASE("erosion_thickness stage writes bt and et relative to the reference length") {
  const MedialComplex plate = fx::make_plate(1.0, 0.6, 10, 6, fx::constant_radius(0.05));
  BasicContext ctx;
  // Shape of max side 2: omega 0.004 x 2 = 0.008 absolute.
  MedialComplex a = plate;
  configured<ErosionThicknessStage>().measure(box_shape(1.0), a, ctx);
  const auto run = run_erosion_thickness(plate, 0.008, 1);
  const auto& bt = a.vertex_props.fields.get("bt");
  const auto& et = a.vertex_props.fields.get("et");
  REQUIRE(bt.size() == plate.num_vertices());
  for (std::size_t v = 0; v < bt.size(); ++v) {
    CHECK(bt[v] == run->burn.bt[v]);
    CHECK(et[v] == Approx(bt[v] - plate.radii[v]).margin(1e-15));
    CHECK(et[v] >= -1e-12);
  }
  CHECK(a.face_props.fields.get("et").size() == plate.faces.size());
  // Without a shape, the complex's own max side (1.0) is the reference.
  MedialComplex b = plate;
  configured<ErosionThicknessStage>().measure(Shape{}, b, ctx);
  const auto run_b = run_erosion_thickness(plate, 0.004, 1);
  for (std::size_t v = 0; v < plate.num_vertices(); ++v) CHECK(b.vertex_props.fields.get("bt")[v] == run_b->burn.bt[v]);
  // Absolute omega.
  MedialComplex c = plate;
  configured<ErosionThicknessStage>({{"relative_to", std::string("absolute")}, {"omega", 0.05}}).measure(box_shape(1.0), c, ctx);
  const auto run_c = run_erosion_thickness(plate, 0.05, 1);
  for (std::size_t v = 0; v < plate.num_vertices(); ++v) CHECK(c.vertex_props.fields.get("bt")[v] == run_c->burn.bt[v]);
}

TEST_CASE("erosion_thickness on a complex without triangles gives ET = 0") {
  MedialComplex mc;
  mc.add_vertex(Vec3(0, 0, 0), 0.5);
  mc.add_vertex(Vec3(1, 0, 0), 0.4);
  mc.add_edge(0, 1);
  BasicContext ctx;
  configured<ErosionThicknessStage>().measure(Shape{}, mc, ctx);
  CHECK(mc.vertex_props.fields.get("et")[0] == 0.0);
  CHECK(mc.vertex_props.fields.get("bt")[1] == 0.4);
}

TEST_CASE("et_medial_curves stage replaces the complex by a tree on a disk-like complex") {
  MedialComplex mc = fx::make_book(1.0, 0.1, 0.3, 0.005, 20, 40);
  BasicContext ctx;
  configured<MedialCurvesStage>().connect(box_shape(0.5), mc, ctx);
  const services::ComplexTopology t = services::complex_topology(mc);
  CHECK(t.b0 == 1);
  CHECK(t.b1 == 0);
  CHECK(mc.faces.empty());
  for (const char* f : {"bt_m", "bt_c", "et_c"}) CHECK(mc.vertex_props.fields.get(f).size() == mc.num_vertices());
  CHECK(mc.vertex_props.labels.get("curve_kind").size() == mc.num_vertices());
  CHECK(mc.edge_props.fields.get("et_c").size() == mc.edges.size());
  mc.validate();
  // The largest ET_C sits on the long page (page 3's tube-like ridge is where curves matter).
  const auto& et_c = mc.vertex_props.fields.get("et_c");
  CHECK(*std::max_element(et_c.begin(), et_c.end()) > 0.05);
}

TEST_CASE("et_skeleton stage keeps the topology and labels curve edges") {
  MedialComplex mc = fx::make_annulus(0.3, 0.6, 4, 24, 0.02);
  const services::ComplexTopology before = services::complex_topology(mc);
  BasicContext ctx;
  configured<EtSkeletonStage>({{"theta2", INFINITY}, {"theta1", INFINITY}}).simplify(box_shape(0.5), mc, ctx);
  mc.validate();
  const services::ComplexTopology after = services::complex_topology(mc);
  CHECK(after.euler == before.euler);
  CHECK(after.b1 == 1);
  CHECK(mc.faces.empty());
  CHECK(mc.edge_props.labels.get("medial_curve").size() == mc.edges.size());
  CHECK(mc.vertex_props.labels.get("et_point").size() == mc.num_vertices());
  // Defaults on the book keep part of the long page as a sheet.
  MedialComplex book = fx::make_book(1.0, 0.1, 0.3, 0.005, 20, 40);
  configured<EtSkeletonStage>().simplify(box_shape(0.5), book, ctx);
  CHECK(!book.faces.empty());
  for (double e : book.face_props.fields.get("et")) CHECK(e > 0.02);
}

TEST_CASE("pure_complex welds, drops degenerate and duplicate triangles, dangling edges and isolated vertices") {
  MedialComplex mc;
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 1, 0), Vec3(5, 5, 5),
                        Vec3(2, 0, 0)})
    mc.add_vertex(p, 0.1);
  mc.add_face(0, 1, 2);
  mc.add_face(1, 4, 2);  // 4 is a copy of 3
  mc.add_face(2, 1, 3);  // the same triangle once 4 is welded to 3
  mc.add_face(0, 0, 1);  // degenerate
  mc.add_edge(1, 6);     // dangling
  mc.add_edge(0, 1);
  mc.vertex_props.fields.add("w", 7) = {0, 1, 2, 3, 4, 5, 6};
  mc.face_props.labels.add("id", 4) = {10, 11, 12, 13};
  mc.generators = {{0}, {1}, {2}, {3}, {4}, {5}, {6}};
  mc.generator_kind = "mesh_vertex";
  const PureComplexReport r = make_pure_complex(mc, 0.0);
  CHECK(r.welded_vertices == 1);
  CHECK(r.degenerate_faces == 1);
  CHECK(r.duplicate_faces == 1);
  CHECK(r.dangling_edges == 1);
  CHECK(r.isolated_vertices == 2);  // 5 and 6
  REQUIRE(mc.num_vertices() == 4);
  CHECK(mc.faces.size() == 2);
  CHECK(mc.edges.size() == 5);
  CHECK(mc.vertex_props.fields.get("w") == std::vector<double>{0, 1, 2, 3});
  CHECK(mc.face_props.labels.get("id") == std::vector<int>{10, 11});
  CHECK(mc.generators[3] == std::vector<Index>{3, 4});
  mc.validate();
  // With a tolerance, nearby centres weld too.
  MedialComplex near;
  near.add_vertex(Vec3(0, 0, 0), 1);
  near.add_vertex(Vec3(1, 0, 0), 1);
  near.add_vertex(Vec3(0, 1, 0), 1);
  near.add_vertex(Vec3(1e-7, 1, 0), 1);
  near.add_face(0, 1, 2);
  near.add_face(0, 1, 3);
  CHECK(make_pure_complex(near, 1e-6).welded_vertices == 1);
  CHECK(near.faces.size() == 1);
}

TEST_CASE("Smallest enclosing ball and object angle") {
  CHECK(min_enclosing_ball({}).radius < 0);
  CHECK(min_enclosing_ball({Vec3(1, 2, 3)}).radius == 0);
  CHECK(min_enclosing_ball({Vec3(0, 0, 0), Vec3(2, 0, 0)}).radius == Approx(1));
  // Equilateral triangle of side 1: circumradius 1/sqrt(3); with its centroid lifted: unchanged.
  const std::vector<Vec3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)};
  CHECK(min_enclosing_ball(tri).radius == Approx(1 / std::sqrt(3.0)));
  // Obtuse triangle: the diameter of the longest side.
  CHECK(min_enclosing_ball({Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0.5, 0)}).radius == Approx(2));
  // Points on a sphere of radius 3 (many, cospherical): radius <= 3, and all inside.
  std::mt19937_64 rng(4);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> pts;
    for (int i = 0; i < 3 + trial; ++i) pts.push_back(3 * Vec3(n(rng), n(rng), n(rng)).normalized());
    const Ball b = min_enclosing_ball(pts);
    CHECK(b.radius <= 3 + 1e-9);
    for (const Vec3& p : pts) CHECK((p - b.centre).norm() <= b.radius * (1 + 1e-9) + 1e-12);
    // Minimal: no smaller ball around the same centre, and brute force over pairs and triples is not smaller.
    double brute = 1e300;
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j) {
        const Vec3 c = 0.5 * (pts[i] + pts[j]);
        double r = 0;
        for (const Vec3& p : pts) r = std::max(r, (p - c).norm());
        brute = std::min(brute, r);
      }
    CHECK(b.radius <= brute + 1e-9);
  }
  CHECK(max_pairwise_angle(Vec3::Zero(), {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0)}) == Approx(M_PI));
  CHECK(max_pairwise_angle(Vec3::Zero(), {Vec3(1, 0, 0), Vec3(0, 2, 0)}) == Approx(M_PI / 2));
  CHECK(max_pairwise_angle(Vec3::Zero(), {Vec3(1, 0, 0)}) == 0);
}

TEST_CASE("Local measures on a Voronoi complex: generators and nearest-point fallback agree") {
  Shape shape;
  shape.mesh = medax::testing::make_ellipsoid(0.5, 0.35, 0.2, 3);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1e-4, 1e-4);
  for (Vec3& p : shape.mesh.vertices) p += Vec3(u(rng), u(rng), u(rng));
  MedialComplex with = fx::interior_voronoi_complex(shape.mesh);
  MedialComplex without = with;
  without.generators.clear();
  without.generator_kind.clear();
  BasicContext ctx;
  for (MedialComplex* mc : {&with, &without}) {
    configured<ObjectAngleStage>().measure(shape, *mc, ctx);
    configured<CircumradiusStage>().measure(shape, *mc, ctx);
    configured<RadiusMeasureStage>().measure(shape, *mc, ctx);
  }
  const auto& a1 = with.vertex_props.fields.get("object_angle");
  const auto& a2 = without.vertex_props.fields.get("object_angle");
  const auto& l1 = with.vertex_props.fields.get("circumradius");
  const auto& l2 = without.vertex_props.fields.get("circumradius");
  std::size_t same = 0;
  for (std::size_t v = 0; v < with.num_vertices(); ++v) {
    CHECK(a1[v] >= 0);
    CHECK(a1[v] <= M_PI + 1e-12);
    CHECK(l1[v] <= with.radii[v] * (1 + 1e-6));  // the generators lie on the medial sphere (near-degenerate supports: round-off)
    CHECK(l1[v] > 0);
    same += std::abs(a1[v] - a2[v]) < 1e-9 && std::abs(l1[v] - l2[v]) < 1e-9;
  }
  CHECK(same >= 0.99 * with.num_vertices());
  CHECK(with.vertex_props.fields.get("radius") == with.radii);
  CHECK(with.face_props.fields.get("object_angle").size() == with.faces.size());
  // No generators and no shape: a clear refusal.
  CHECK_THROWS_AS(configured<ObjectAngleStage>().measure(Shape{}, without, ctx), std::invalid_argument);
}

#ifdef MEDAX_ET_PLUGIN
TEST_CASE("The erosion_thickness package loads and runs in a pipeline", "[pipeline]") {
  Registry registry;
  REQUIRE(registry.load_file(MEDAX_ET_PLUGIN));
  const std::pair<const char*, Role> stages[] = {
      {"erosion_thickness", Role::Significance}, {"radius_measure", Role::Significance},
      {"object_angle", Role::Significance},      {"circumradius", Role::Significance},
      {"et_medial_curves", Role::Connectivity},  {"et_skeleton", Role::Simplification},
      {"pure_complex", Role::Simplification}};
  for (const auto& [name, role] : stages) {
    const RegisteredStage* stage = registry.find(name);
    REQUIRE(stage);
    CHECK(stage->info().role == role);
    CHECK(stage->info().doc == "docs/plugins/erosion_thickness.md");
  }
  const auto dir = test::scratch_dir("erosion_thickness_pipeline");
  write_mesh(dir / "box.off", medax::testing::make_box(0.5, 0.5, 0.5, 1));
  write_medial(dir / "book.ma", fx::make_book(1.0, 0.1, 0.3, 0.005, 20, 40));
  for (const char* last : {"et_skeleton", "et_medial_curves"}) {
    const RunResult result = test::run_yaml_text(dir,
                                                 "name: et\nseed: 0\ninput: box.off\nmedial_input: book.ma\n"
                                                 "stages:\n"
                                                 "  - plugin: pure_complex\n"
                                                 "  - plugin: erosion_thickness\n"
                                                 "    params: {omega: 0.01}\n"
                                                 "  - plugin: " + std::string(last) + "\n    params: {omega: 0.01}\n"
                                                 "outputs: {medial: [ma, ply]}\n",
                                                 registry, last);
    INFO(result.error);
    REQUIRE(result.ok);
    const MedialComplex out = read_ma(dir / last / "medial.ma");
    const services::ComplexTopology t = services::complex_topology(out);
    CHECK(t.b0 == 1);
    CHECK(t.b1 == 0);
    std::ifstream ply(dir / last / "medial.ply");
    std::stringstream text;
    text << ply.rdbuf();
    CHECK(text.str().find(std::string(last) == "et_skeleton" ? "et_point" : "et_c") != std::string::npos);
  }
}
#endif

#ifdef MEDAX_ET_PLUGIN_DIR
TEST_CASE("pipelines/voronoi_et.yaml runs on the bundled mesh and keeps the topology", "[pipeline]") {
  // Needs the conditioning, voronoi and evaluation packages too (built beside this one).
  Registry registry;
  const std::filesystem::path dir = MEDAX_ET_PLUGIN_DIR;
  for (const char* package : {"conditioning", "voronoi", "evaluation", "erosion_thickness"}) {
    const auto file = dir / (std::string("libmedax_") + package + ".so");
    if (!std::filesystem::exists(file) || !registry.load_file(file)) {
      WARN("package " << package << " is not built in " << dir << "; skipped");
      return;
    }
  }
  const std::filesystem::path out_dir = test::scratch_dir("voronoi_et_pipeline");
  const RunResult result = test::run_quietly(test::source_dir() / "pipelines" / "voronoi_et.yaml", registry, out_dir);
  INFO(result.error);
  REQUIRE(result.ok);
  std::ifstream in(out_dir / "metrics.json");
  std::stringstream json;
  json << in.rdbuf();
  // spot is genus 0: the skeleton is connected and has no cycle or cavity.
  const MedialComplex skeleton = read_ma(out_dir / "medial.ma");
  const services::ComplexTopology t = services::complex_topology(skeleton);
  CHECK(t.b0 == 1);
  CHECK(t.b1 == 0);
  CHECK(t.b2 == 0);
  CHECK(!skeleton.faces.empty());
  CHECK(json.str().find("\"topology\"") != std::string::npos);
}
#endif
