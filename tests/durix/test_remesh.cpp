// The remesh route of delaunay_surface (notes §1.2 option 2) and its fallback from DZM07.
#include "fixtures.hpp"
#include "remesh_fallback.hpp"
#include "stages.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/mesh_check.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <random>
#include <string>
#include <vector>

using namespace medax;
using namespace medax::durix;

namespace {

/// A thin L-shaped bar (three unit cubes squashed to 0.1 across, faces split 3 × 3) with its
/// vertices jittered by up to 0.01: DZM07's splits cascade between the close, nearly parallel
/// sides until the insertion budget is spent (measured: "gave up" in a few milliseconds).
SurfaceMesh thin_l_bar() {
  SurfaceMesh m = test::cube_union({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 3);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (Vec3& p : m.vertices) p = p.cwiseProduct(Vec3(1, 0.1, 1)) + Vec3(jitter(rng), jitter(rng), jitter(rng));
  return m;
}

/// Largest distance from the vertices of `from` to the surface `to`.
double one_sided_distance(const SurfaceMesh& from, const SurfaceMesh& to) {
  const std::vector<double> d = services::SurfaceDistance(to).distances(from.vertices);
  return *std::max_element(d.begin(), d.end());
}

void check_conversion(const SurfaceMesh& input, const SurfaceMesh& out) {
  CHECK(check_delaunay_mesh(out).ok());
  services::MeshCheckOptions options;
  options.self_intersections = false;
  const services::MeshReport before = services::check_mesh(input, options), after = services::check_mesh(out, options);
  INFO(after.describe_problems());
  CHECK(after.ok());
  REQUIRE(after.genus);
  CHECK(*after.genus == *before.genus);
  CHECK(after.components == before.components);
}

struct RecordingContext : BasicContext {
  std::vector<std::string> warnings;
  void warn(std::string_view message) override { warnings.emplace_back(message); }
};

}  // namespace

TEST_CASE("durix remesh fallback: DZM07 fails on a thin jittered L-bar and the remesh converts it",
          "[durix][delaunay_surface][remesh]") {
  const SurfaceMesh bar = thin_l_bar();
  REQUIRE(services::check_mesh(bar).ok());
  CHECK_THROWS_WITH(make_delaunay_mesh(bar), Catch::Contains("gave up"));
  const DelaunaySurfaceResult r = make_delaunay_surface(bar);
  CHECK(r.method == DelaunayMethod::Remesh);
  CHECK_THAT(r.dzm07_failure, Catch::Contains("gave up"));
  check_conversion(bar, r.mesh);
  CHECK(one_sided_distance(r.mesh, bar) < 0.01 * bbox_diagonal(bar.vertices));
}

TEST_CASE("durix remesh fallback: fallback none refuses the L-bar and says what to do", "[durix][delaunay_surface][remesh]") {
  DelaunaySurfaceOptions options;
  options.fallback = DelaunayFallback::None;
  try {
    make_delaunay_surface(thin_l_bar(), options);
    FAIL("expected a refusal");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains("gave up") && Catch::Contains("fallback: remesh"));
  }
}

TEST_CASE("durix remesh fallback: two runs give identical meshes", "[durix][delaunay_surface][remesh]") {
  const SurfaceMesh bar = thin_l_bar();
  const DelaunaySurfaceResult a = make_delaunay_surface(bar), b = make_delaunay_surface(bar);
  REQUIRE(a.mesh.vertices.size() == b.mesh.vertices.size());
  CHECK(a.mesh.vertices == b.mesh.vertices);
  CHECK(a.mesh.faces == b.mesh.faces);
}

TEST_CASE("durix method remesh keeps the genus and stays near a sphere and a torus", "[durix][delaunay_surface][remesh]") {
  const std::vector<std::pair<std::string, SurfaceMesh>> shapes = {
      {"sphere", testing::make_sphere(1.0, 3)}, {"torus", testing::make_torus(1.0, 0.35, 48, 16)}};
  DelaunaySurfaceOptions options;
  options.method = DelaunayMethod::Remesh;
  for (const auto& [name, mesh] : shapes) {
    INFO(name);
    const DelaunaySurfaceResult r = make_delaunay_surface(mesh, options);
    CHECK(r.method == DelaunayMethod::Remesh);
    CHECK(r.dzm07_failure.empty());
    check_conversion(mesh, r.mesh);
    // Same order of size as the input, and within a small fraction of the diagonal both ways.
    CHECK(r.mesh.vertices.size() > mesh.vertices.size() / 3);
    CHECK(r.mesh.vertices.size() < mesh.vertices.size() * 3);
    const double diagonal = bbox_diagonal(mesh.vertices);
    CHECK(one_sided_distance(r.mesh, mesh) < 0.005 * diagonal);
    CHECK(one_sided_distance(mesh, r.mesh) < 0.01 * diagonal);
  }
}

TEST_CASE("durix remesh: a result that lost a component is refused, saying what to do", "[durix][delaunay_surface][remesh]") {
  // A small sphere beside a big one, and initial points taken from the big one only: the mesher
  // never finds the small one, and the component count check catches it.
  SurfaceMesh two = testing::make_sphere(1.0, 3);
  const SurfaceMesh small = testing::make_sphere(0.05, 1);
  const Index offset = static_cast<Index>(two.vertices.size());
  for (const Vec3& p : small.vertices) two.vertices.push_back(p + Vec3(3, 0, 0));
  for (const Tri& t : small.faces) two.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  DelaunaySurfaceOptions options;
  options.method = DelaunayMethod::Remesh;
  options.remesh.initial_points = 4;
  options.remesh_attempts = 1;
  CHECK_THROWS_WITH(make_delaunay_surface(two, options),
                    Catch::Contains("1 component(s), the input genus 0 in 2") && Catch::Contains("lower remesh_facet_size"));
}

TEST_CASE("durix delaunay_surface stage: the fallback warns, fallback none refuses", "[durix][delaunay_surface][stages]") {
  DelaunaySurfaceStage stage;  // at its declared defaults: fallback: remesh
  Shape shape;
  shape.mesh = thin_l_bar();
  RecordingContext ctx;
  stage.condition(shape, ctx);
  REQUIRE(ctx.warnings.size() == 1);
  CHECK_THAT(ctx.warnings[0], Catch::Contains("DZM07") && Catch::Contains("remesh"));
  CHECK(check_delaunay_mesh(shape.mesh).ok());

  ParamSet params;
  params.set("fallback", std::string("none"));
  stage.configure(params);
  shape.mesh = thin_l_bar();
  CHECK_THROWS_WITH(stage.condition(shape, ctx),
                    Catch::Contains("cannot convert") && Catch::Contains("fallback"));
}

TEST_CASE("durix remesh: an attempt that does not finish is retried at twice the facet distance", "[durix][remesh]") {
  // A vertex cap that the first attempt (a fine facet distance) cannot meet and the coarser
  // retries can: the conversion succeeds on a later attempt, and the refusal when attempts run
  // out lists every attempt.
  const SurfaceMesh sphere = testing::make_sphere(1.0, 3);
  DelaunaySurfaceOptions options;
  options.method = DelaunayMethod::Remesh;
  // Only the distance bounds the facets; from 50 seed points the mesher needs about 3500
  // vertices at facet distance 0.0005 and 1200 at 0.001 (measured).
  options.remesh.facet_size = 100;
  options.remesh.facet_distance = 0.0005;
  options.remesh.initial_points = 50;
  options.remesh.max_vertices_factor = 0;
  options.remesh.max_vertices_base = 2000;
  options.remesh_attempts = 1;
  CHECK_THROWS_WITH(make_delaunay_surface(sphere, options),
                    Catch::Contains("attempt 1 at facet_size 100, facet_distance 0.0005: the remesh reached its cap") &&
                        Catch::Contains("raise remesh_facet_distance"));
  options.remesh_attempts = 3;
  const DelaunaySurfaceResult r = make_delaunay_surface(sphere, options);
  CHECK(r.method == DelaunayMethod::Remesh);
  CHECK(r.remesh.facet_distance == Approx(0.001 * bbox_diagonal(sphere.vertices)));
  check_conversion(sphere, r.mesh);
}
