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
#include <medax/plugin.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>
#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
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
  ParamSet params;
  for (const auto& [name, value] : overrides) params.set(name, value);
  stage.configure(params);
  return stage;
}

std::vector<std::string> param_names(const StageInfo& info) {
  std::vector<std::string> names;
  for (const ParamSpec& p : info.params) names.push_back(p.name);
  return names;
}

std::string what_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
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
  configured<ErosionThicknessStage>().measure(box_shape(0.5), mc, ctx);
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
  configured<ErosionThicknessStage>().measure(box_shape(0.5), mc, ctx);
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
  configured<ErosionThicknessStage>().measure(box_shape(0.5), book, ctx);
  configured<EtSkeletonStage>().simplify(box_shape(0.5), book, ctx);
  CHECK(!book.faces.empty());
  for (double e : book.face_props.fields.get("et")) CHECK(e > 0.02);
}

namespace {

/// A context over a scene's data whose stage id can be set, to run stages one after another as
/// the runner does (prepare, then run, each with its own id).
class SceneContext : public Context {
 public:
  explicit SceneContext(SceneData& data) : data_(data) {}
  void info(std::string_view) override {}
  void warn(std::string_view) override {}
  void progress(double, std::string_view) override {}
  bool cancelled() const override { return false; }
  std::mt19937_64& rng() override { return rng_; }
  std::uint64_t seed() const override { return 0; }
  std::filesystem::path write_output(const std::string&, const std::function<void(std::ostream&)>&) override {
    return {};
  }
  const std::string& stage_id() const override { return id; }
  SceneData& data() override { return data_; }
  std::string id = "stage";

 private:
  SceneData& data_;
  std::mt19937_64 rng_;
};

void run_stage(Stage& stage, const std::string& id, Scene& scene) {
  SceneContext ctx(scene.data);
  ctx.id = id;
  stage.prepare(scene);
  stage.run(scene, ctx);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Equal elements and columns, doubles compared bit for bit (NaN included).
void require_identical(const MedialComplex& a, const MedialComplex& b) {
  REQUIRE(a.num_vertices() == b.num_vertices());
  for (std::size_t v = 0; v < a.num_vertices(); ++v) REQUIRE(std::memcmp(&a.centres[v], &b.centres[v], sizeof(Vec3)) == 0);
  CHECK(same_bits(a.radii, b.radii));
  CHECK(a.edges == b.edges);
  CHECK(a.faces == b.faces);
  for (Element e : {Element::Vertex, Element::Edge, Element::Face}) {
    const ElementProperties &pa = a.props(e), &pb = b.props(e);
    REQUIRE(pa.fields.all().size() == pb.fields.all().size());
    for (const auto& [name, column] : pa.fields.all()) {
      INFO(name);
      REQUIRE(pb.fields.has(name));
      CHECK(same_bits(column, pb.fields.get(name)));
    }
    CHECK(pa.labels.all() == pb.labels.all());
  }
}

}  // namespace

TEST_CASE("The burning stages declare their parameters once; the later stages take the burn's") {
  CHECK(param_names(stage_info<ErosionThicknessStage>()) ==
        std::vector<std::string>{"omega", "min_samples", "relative_to", "write_forest"});
  CHECK(param_names(stage_info<MedialCurvesStage>()).empty());
  CHECK(param_names(stage_info<EtSkeletonStage>()) == std::vector<std::string>{"theta2", "theta1", "phi2", "phi1"});
  CHECK(param_names(stage_info<PureComplexStage>()) == std::vector<std::string>{"weld_tolerance"});
  CHECK(param_names(stage_info<ObjectAngleStage>()) == std::vector<std::string>{"tolerance"});
  const StageInfo et = stage_info<ErosionThicknessStage>();
  CHECK(et.params[2].choices == std::vector<std::string>{"shape_max_side", "complex_max_side", "absolute"});
  CHECK(et.params[2].default_text() == "shape_max_side");
  // The defaults live in the options structs.
  CHECK(std::get<double>(et.params[0].default_value) == BurnOptions{}.omega);
  CHECK(std::get<double>(stage_info<EtSkeletonStage>().params[2].default_value) == SkeletonOptions{}.phi2);
}

TEST_CASE("One burn feeds et_medial_curves and et_skeleton: the same complexes as burning in each stage") {
  const Shape shape = box_shape(0.5);  // L = 1
  for (const MedialComplex& input :
       {fx::make_book(1.0, 0.1, 0.3, 0.005, 20, 40), fx::make_annulus(0.3, 0.6, 4, 24, 0.02)}) {
    // The stages, as the runner calls them.
    Scene scene;
    scene.shape = shape;
    scene.medial = input;
    ErosionThicknessStage et = configured<ErosionThicknessStage>({{"omega", 0.01}});
    run_stage(et, "erosion_thickness", scene);
    const MedialComplex with_et = *scene.medial;
    Scene curves_scene = scene;
    MedialCurvesStage curves;
    run_stage(curves, "et_medial_curves", curves_scene);
    EtSkeletonStage skeleton = configured<EtSkeletonStage>({{"theta2", 0.03}, {"phi2", 0.001}});
    run_stage(skeleton, "et_skeleton", scene);
    // What the stages computed before the burn was shared: each burned the complex itself.
    const auto run = run_erosion_thickness(with_et, 0.01, 1);
    const Subdivision sub = build_subdivision(run->graph, run->burn);
    MedialComplex expected_curves = with_et;
    store_medial_curves(extract_medial_curves(run->graph, sub), expected_curves);
    require_identical(*curves_scene.medial, expected_curves);
    SkeletonOptions o;
    o.theta2 = 0.03;
    o.phi2 = 0.001;
    MedialComplex expected_skeleton;
    store_skeleton(compute_skeleton(run->graph, sub, run->loose_edges, o), expected_skeleton);
    require_identical(*scene.medial, expected_skeleton);
  }
}

TEST_CASE("et_medial_curves and et_skeleton need the burn of the complex they get") {
  const MedialComplex book = fx::make_book(1.0, 0.1, 0.3, 0.005, 20, 40);
  Scene scene;
  scene.shape = box_shape(0.5);
  scene.medial = book;
  // No burn: the error names the stage to put first.
  EtSkeletonStage skeleton;
  MedialCurvesStage curves;
  CHECK_THROWS_AS(skeleton.prepare(scene), MissingData);
  CHECK(what_of([&] { curves.prepare(scene); }).find("`erosion_thickness`") != std::string::npos);
  BasicContext ctx;
  MedialComplex copy = book;
  CHECK_THROWS_AS(curves.connect(scene.shape, copy, ctx), MissingData);
  // After et_medial_curves replaced the complex, et_skeleton refuses the old burn and names it.
  ErosionThicknessStage et;
  run_stage(et, "erosion_thickness", scene);
  run_stage(curves, "curves", scene);
  const std::string stale = what_of([&] { run_stage(skeleton, "et_skeleton", scene); });
  INFO(stale);
  CHECK(stale.find("not the one `erosion_thickness` burned") != std::string::npos);
  CHECK(stale.find("`curves` replaced it") != std::string::npos);
  CHECK(stale.find("run `erosion_thickness` right before this stage") != std::string::npos);
  // A burn of the curves themselves is fine (what et_skeleton used to do after the curves).
  run_stage(et, "erosion_thickness_2", scene);
  CHECK_NOTHROW(run_stage(skeleton, "et_skeleton", scene));
  // Any other change of the complex is refused too, without a name.
  Scene edited;
  edited.shape = box_shape(0.5);
  edited.medial = book;
  run_stage(et, "erosion_thickness", edited);
  edited.medial->radii[3] *= 1.5;
  const std::string changed = what_of([&] { skeleton.prepare(edited); });
  INFO(changed);
  CHECK(changed.find("a stage after it changed the complex") != std::string::npos);
  // Fields added in between (another measure) do not change the complex.
  edited.medial = book;
  run_stage(et, "erosion_thickness", edited);
  RadiusMeasureStage radius;
  run_stage(radius, "radius_measure", edited);
  CHECK_NOTHROW(run_stage(skeleton, "et_skeleton", edited));
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
  mc.edge_props.labels.add("sheet", 2) = {7, 8};
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
  CHECK(mc.edge_props.empty());  // the edges are rebuilt as the faces' sides
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
  CHECK(with.vertex_props.fields.get("medial_radius") == with.radii);
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
                                                 "  - plugin: " + std::string(last) + "\n"
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
  // et_skeleton after et_medial_curves: the burn is of the complex before the curves.
  const std::string head = "name: et\nseed: 0\ninput: box.off\nmedial_input: book.ma\nstages:\n"
                           "  - plugin: pure_complex\n  - plugin: erosion_thickness\n  - plugin: et_medial_curves\n";
  const RunResult stale = test::run_yaml_text(dir, head + "  - plugin: et_skeleton\n", registry, "stale");
  CHECK(!stale.ok);
  CHECK(stale.failed_stage == "et_skeleton");
  CHECK(stale.error.find("et_skeleton: the complex is not the one `erosion_thickness` burned") != std::string::npos);
  CHECK(stale.error.find("`et_medial_curves` replaced it") != std::string::npos);
  const RunResult again = test::run_yaml_text(
      dir, head + "  - {plugin: erosion_thickness, id: burn_curves}\n  - plugin: et_skeleton\n", registry, "again");
  INFO(again.error);
  CHECK(again.ok);
  // Without erosion_thickness, the error says which stage to put first.
  const RunResult missing = test::run_yaml_text(
      dir, "name: et\nseed: 0\ninput: box.off\nmedial_input: book.ma\nstages:\n  - plugin: et_skeleton\n",
      registry, "missing");
  CHECK(!missing.ok);
  CHECK(missing.error.find("put a `erosion_thickness` stage before this one") != std::string::npos);
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
