// The normalize, repair and sample stages, loaded from the built plugin as a pipeline would.
#include "conditioning_test_support.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/mesh_check.hpp>
#include <medax/services/poisson.hpp>
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>

#include <numeric>

using namespace medax;

namespace {

struct Box {
  Vec3 lo, hi;
};

Box bounds(const std::vector<Vec3>& points) {
  Box b{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (const Vec3& p : points) b.lo = b.lo.cwiseMin(p), b.hi = b.hi.cwiseMax(p);
  return b;
}

std::string refusal(const std::filesystem::path& path, const std::map<std::string, ParamValue>& settings = {}) {
  auto stage = test::make_stage("repair", settings);
  test::RecordingContext ctx;
  try {
    test::run_stage(*stage, test::shape_of(path), ctx);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("the conditioning plugin registers normalize, repair and sample", "[stages]") {
  const Registry& registry = test::conditioning_registry();
  CHECK(registry.errors().empty());
  for (const char* name : {"normalize", "repair", "sample"}) {
    INFO(name);
    const RegisteredStage* stage = registry.find(name);
    REQUIRE(stage != nullptr);
    CHECK(stage->info().role == Role::Conditioning);
    CHECK(stage->package->name == "conditioning");
    CHECK(contains(stage->info().doc, "docs/plugins/conditioning.md"));
    CHECK(std::filesystem::exists(test::source_dir() / "docs/plugins/conditioning.md"));
    for (const ParamSpec& p : stage->info().params) CHECK_FALSE(p.doc.empty());
  }
}

TEST_CASE("normalize: unit diagonal or longest side, centred, and to_input maps back exactly", "[stages]") {
  const std::string mode = GENERATE(as<std::string>{}, "diagonal", "max_side");
  // Organic, high-genus, CAD and thin shapes of different scales (bbox diagonals 229 to 0.17).
  for (const char* name : {"armadillo.off", "cheese.off", "anchor.off", "turbine.off"}) {
    INFO(name << " " << mode);
    Shape shape = test::shape_of(test::corpus_mesh(name));
    // A frame already moved by an earlier stage: normalize composes with it.
    shape.to_input = Similarity{2.5, Vec3(1, -2, 3)};
    std::mt19937_64 rng(1);
    shape.samples = services::sample_uniform(shape.mesh, 200, rng);
    const Shape before = shape;
    const double input_diag = bbox_diagonal(before.mesh.vertices) * 2.5;  // in the input frame

    auto stage = test::make_stage("normalize", {{"mode", mode}});
    test::RecordingContext ctx;
    const Shape after = test::run_stage(*stage, shape, ctx).shape;
    CHECK(ctx.logged("scaled by"));

    const Box box = bounds(after.mesh.vertices);
    const Vec3 extent = box.hi - box.lo;
    if (mode == "diagonal") CHECK(extent.norm() == Approx(1.0).epsilon(1e-12));
    else CHECK(extent.maxCoeff() == Approx(1.0).epsilon(1e-12));
    CHECK((0.5 * (box.lo + box.hi)).norm() < 1e-12);

    // Round trip: every vertex and sample maps back to where it was, to 1e-12 of the size.
    double worst = 0;
    for (std::size_t i = 0; i < after.mesh.vertices.size(); ++i)
      worst = std::max(worst, (after.to_input.apply(after.mesh.vertices[i]) -
                               before.to_input.apply(before.mesh.vertices[i])).norm());
    for (std::size_t i = 0; i < after.samples.size(); ++i)
      worst = std::max(worst, (after.to_input.apply(after.samples.points[i]) -
                               before.to_input.apply(before.samples.points[i])).norm());
    CHECK(worst <= 1e-12 * input_diag);
    CHECK(after.mesh.faces == before.mesh.faces);
    CHECK(after.samples.normals == before.samples.normals);
    const double scale = after.to_input.scale / before.to_input.scale;  // the normalising size
    const double areas_before = std::accumulate(before.samples.areas.begin(), before.samples.areas.end(), 0.0);
    const double areas_after = std::accumulate(after.samples.areas.begin(), after.samples.areas.end(), 0.0);
    CHECK(areas_after == Approx(areas_before / (scale * scale)).epsilon(1e-12));
    CHECK(areas_after == Approx(services::surface_area(after.mesh)).epsilon(1e-9));
  }
}

TEST_CASE("normalize refuses a shape without extent", "[stages]") {
  auto stage = test::make_stage("normalize");
  Scene empty;
  CHECK_THROWS_AS(stage->prepare(empty), std::invalid_argument);
  Scene point;
  point.shape.mesh.vertices = {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)};
  point.shape.mesh.faces = {{0, 1, 2}};
  CHECK_THROWS_AS(stage->prepare(point), std::invalid_argument);
}

// The counts of the CGAL meshes are exact counts on the files (see test_mesh_check.cpp).
TEST_CASE("repair refuses each broken mesh, naming its problems and their fixes", "[stages]") {
  {
    const std::string text = refusal(test::corpus_mesh("bad/pig.off"));
    INFO(text);
    CHECK(text.rfind("refusing pig.off", 0) == 0);  // the runner puts "repair: " before it
    CHECK(contains(text, "7 boundary loops (holes; 55 boundary edges): run `repair` with fill_holes: true"));
    CHECK_FALSE(contains(text, "unreferenced"));
    CHECK(contains(text, "3 self-intersecting triangle pairs"));  // CGAL self_intersections: 3 too
  }
  {
    const std::string text = refusal(test::corpus_mesh("bad/elephant-with-holes.off"));
    INFO(text);
    CHECK(contains(text, "65 duplicate vertices"));
    CHECK(contains(text, "1353 boundary edges"));
  }
  {
    const std::string text = refusal(test::corpus_mesh("bad/degtri_sliding.off"));
    INFO(text);
    CHECK(contains(text, "4 degenerate faces"));
  }
  const auto dir = test::data_dir() / "bad";
  {
    const std::string text = refusal(dir / "thingi10k-68251.stl");
    INFO(text);
    CHECK(contains(text, "8 non-manifold edges"));
    CHECK(contains(text, "not watertight"));
    CHECK(contains(text, "88 self-intersecting triangle pairs"));
  }
  {
    const std::string text = refusal(test::corpus_mesh("bad/cow.off"));
    INFO(text);
    CHECK(contains(text, "101 self-intersecting triangle pairs"));
    CHECK(contains(text, "remove_self_intersections: true"));
    CHECK(contains(text, "1 duplicate vertex"));
    CHECK_FALSE(contains(text, "holes"));
    CHECK_FALSE(contains(text, "non-manifold"));
  }
}

TEST_CASE("repair with repair: true closes pig.off and refuses the rest with the reason", "[stages]") {
  {
    auto stage = test::make_stage("repair", {{"repair", true}});
    test::RecordingContext ctx;
    const Shape input = test::shape_of(test::corpus_mesh("bad/pig.off"));
    const Shape out = test::run_stage(*stage, input, ctx).shape;
    const auto check = services::check_mesh(out.mesh);
    CHECK(check.valid_solid());
    CHECK(check.genus == std::optional<long long>(0));
    CHECK(test::bbox_diag(out.mesh) == Approx(test::bbox_diag(input.mesh)).epsilon(0.01));
    CHECK(ctx.logged("filled 7 holes"));
  }
  for (const auto& path : {test::data_dir() / "bad" / "thingi10k-68251.stl", test::corpus_mesh("bad/cow.off")}) {
    const std::string text = refusal(path, {{"repair", true}});
    INFO(path.filename().string() << "\n" << text);
    CHECK(contains(text, "did not give a valid mesh"));
    CHECK(contains(text, "could not remove the self-intersections"));
    CHECK(contains(text, "What remains after repair:"));
    CHECK(contains(text, "self-intersecting triangle pair"));
    CHECK(contains(text, "Fix these in a mesh editor"));
  }
}

TEST_CASE("repair passes good meshes unchanged", "[stages]") {
  // A varied subset (every good mesh passes the check itself: test_mesh_check.cpp).
  auto stage = test::make_stage("repair");
  for (const auto& path : {test::data_dir() / "cube.off", test::data_dir() / "torus.obj", test::corpus_mesh("armadillo.off"),
                           test::corpus_mesh("cheese.off"), test::corpus_mesh("couplingdown.off"),
                           test::corpus_mesh("turbine.off")}) {
    INFO(path.filename().string());
    test::RecordingContext ctx;
    const Shape input = test::shape_of(path);
    const Shape out = test::run_stage(*stage, input, ctx).shape;
    CHECK(out.mesh.vertices == input.mesh.vertices);
    CHECK(out.mesh.faces == input.mesh.faces);
    CHECK(ctx.logged("valid as it is"));
    CHECK(ctx.warnings.empty());
  }
}

TEST_CASE("repair fixes cheap problems without being asked, and logs them", "[stages]") {
  SECTION("inward orientation") {
    Shape shape = test::shape_of(test::source_dir() / "pipelines" / "meshes" / "spot.obj");
    const SurfaceMesh original = shape.mesh;
    shape.mesh = test::reversed(shape.mesh);
    auto stage = test::make_stage("repair");
    test::RecordingContext ctx;
    const Shape out = test::run_stage(*stage, shape, ctx).shape;
    CHECK(services::check_mesh(out.mesh).outward);
    std::size_t same = 0;
    for (std::size_t f = 0; f < original.faces.size(); ++f)
      same += test::same_oriented_face(out.mesh.faces[f], original.faces[f]);
    CHECK(same == original.faces.size());
    CHECK(ctx.logged("flipped"));
  }
  SECTION("duplicate vertices (a polygon soup), and stale samples are dropped") {
    Shape shape;
    shape.mesh = test::exploded(testing::make_sphere(1.0, 2));
    shape.samples.points = {Vec3(0, 0, 1)};
    shape.samples.normals = {Vec3(0, 0, 1)};
    shape.samples.areas = {1.0};
    auto stage = test::make_stage("repair");
    test::RecordingContext ctx;
    const Shape out = test::run_stage(*stage, shape, ctx).shape;
    CHECK(out.mesh.vertices.size() == testing::make_sphere(1.0, 2).vertices.size());
    CHECK(services::check_mesh(out.mesh).ok());
    CHECK(ctx.logged("merged"));
    CHECK(out.samples.empty());
    CHECK(ctx.logged("put `sample` after `repair`"));
  }
}

TEST_CASE("repair checks its parameters and input before any work", "[stages]") {
  Scene no_mesh;
  CHECK_THROWS_AS(test::make_stage("repair")->prepare(no_mesh), std::invalid_argument);
  Scene scene;
  scene.shape.mesh = test::tetrahedron();
  for (const char* removal : {"remove_self_intersections", "repair"}) {
    INFO(removal);
    auto blind = test::make_stage("repair", {{removal, true}, {"check_self_intersections", false}});
    CHECK_THROWS_WITH(blind->check_params(), Catch::Contains("needs check_self_intersections: true"));
    CHECK_THROWS_AS(blind->prepare(scene), std::invalid_argument);
  }
  CHECK_NOTHROW(test::make_stage("repair", {{"check_self_intersections", false}})->check_params());
}

TEST_CASE("sample: every method gives unit normals on the surface and areas summing to its area", "[stages]") {
  const SurfaceMesh mesh = read_mesh(test::data_dir() / "sphere.obj");
  const services::SurfaceDistance distance(mesh);
  const auto face_normals = services::face_normals(mesh);
  const double area = services::surface_area(mesh);
  for (const std::string method : {"uniform", "poisson", "vertices"}) {
    INFO(method);
    auto stage = test::make_stage("sample", {{"method", method}, {"count", 2000LL}});
    test::RecordingContext ctx(42);
    Shape shape;
    shape.mesh = mesh;
    const OrientedSamples s = test::run_stage(*stage, shape, ctx).shape.samples;
    CHECK(s.size() == (method == "vertices" ? mesh.vertices.size() : 2000u));
    REQUIRE(s.normals.size() == s.size());
    REQUIRE(s.areas.size() == s.size());
    CHECK(std::accumulate(s.areas.begin(), s.areas.end(), 0.0) == Approx(area).epsilon(1e-9));
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto closest = distance.closest(s.points[i]);
      CHECK(closest.distance < 1e-12);
      CHECK(std::abs(s.normals[i].norm() - 1.0) < 1e-12);
      CHECK(s.normals[i].dot(face_normals[closest.face]) > 0.98);  // outward, like the surface
      CHECK(s.areas[i] > 0);
    }
    CHECK(ctx.logged("took"));
  }
}

TEST_CASE("sample: the same seed gives the same samples", "[stages]") {
  Shape shape;
  shape.mesh = read_mesh(test::corpus_mesh("elephant.off"));
  for (const std::string method : {"uniform", "poisson"}) {
    INFO(method);
    auto stage = test::make_stage("sample", {{"method", method}, {"count", 1000LL}});
    test::RecordingContext a(5), b(5), c(6);
    const auto sa = test::run_stage(*stage, shape, a).shape.samples;
    const auto sb = test::run_stage(*stage, shape, b).shape.samples;
    const auto sc = test::run_stage(*stage, shape, c).shape.samples;
    CHECK(sa.points == sb.points);
    CHECK(sa.normals == sb.normals);
    CHECK(sa.areas == sb.areas);
    CHECK(sa.points != sc.points);
  }
}

TEST_CASE("sample: Poisson-disk respects its minimum distance", "[stages]") {
  Shape shape;
  shape.mesh = read_mesh(test::corpus_mesh("extra/hand.off"));
  const double area = services::surface_area(shape.mesh);
  SECTION("by count: exact count, at least 0.6 of the packing spacing") {
    auto stage = test::make_stage("sample", {{"count", 4000LL}});
    test::RecordingContext ctx(1);
    const auto s = test::run_stage(*stage, shape, ctx).shape.samples;
    CHECK(s.size() == 4000);
    CHECK(services::min_sample_distance(s) >= 0.6 * services::poisson_packing_distance(area, 4000));
    CHECK(ctx.logged("minimum distance"));
  }
  SECTION("by count from dart-thrown candidates: exact count, at least 0.6 of the packing spacing") {
    auto darts = test::make_stage("sample", {{"count", 4000LL}, {"candidates", std::string("darts")}});
    auto uniform = test::make_stage("sample", {{"count", 4000LL}});
    test::RecordingContext ctx(1), uniform_ctx(1);
    const auto s = test::run_stage(*darts, shape, ctx).shape.samples;
    CHECK(s.size() == 4000);
    CHECK(services::min_sample_distance(s) >= 0.6 * services::poisson_packing_distance(area, 4000));
    CHECK(ctx.logged("dart-thrown candidates"));
    CHECK(s.points != test::run_stage(*uniform, shape, uniform_ctx).shape.samples.points);
  }
  SECTION("by radius: no two samples closer than min_distance") {
    const double r = 0.01;
    auto stage = test::make_stage("sample", {{"min_distance", r}});
    test::RecordingContext ctx(1);
    const auto s = test::run_stage(*stage, shape, ctx).shape.samples;
    CHECK(s.size() > 100);
    CHECK(services::min_sample_distance(s) >= r);
  }
}

TEST_CASE("sample: Poisson-disk reports progress and stops when the user cancels", "[stages]") {
  // A context whose user has already pressed Ctrl-C: the first progress report stops the stage.
  struct CancelledContext : test::RecordingContext {
    using RecordingContext::RecordingContext;
    bool cancelled() const override { return true; }
  };
  Shape shape;
  shape.mesh = read_mesh(test::corpus_mesh("fandisk.off"));
  for (const std::string candidates : {"uniform", "darts"}) {
    INFO(candidates);
    auto stage = test::make_stage("sample", {{"count", 2000LL}, {"candidates", candidates}});
    CancelledContext ctx(1);
    CHECK_THROWS_AS(test::run_stage(*stage, shape, ctx), Cancelled);
    CHECK_FALSE(ctx.logged("took"));
  }
}

TEST_CASE("sample refuses a shape without a mesh", "[stages]") {
  Scene scene;
  CHECK_THROWS_AS(test::make_stage("sample")->prepare(scene), std::invalid_argument);
}
