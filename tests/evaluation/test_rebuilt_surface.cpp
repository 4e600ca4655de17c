// The evaluation stages on a representation that publishes more than a medial complex: a rebuilt
// surface (kReconstructedSurface) measured instead of the envelope, and a representation size
// (kRepresentationSize) counted instead of the complex's elements.
#include "rebuilt_surface.hpp"
#include "shape_fixtures.hpp"
#include "stages.hpp"

#include <medax/representation_size.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace medax;

namespace {

/// Runs the reconstruction stage with `rebuilt` published as the rebuilt surface.
Metrics measure_published(const Shape& shape, const SurfaceMesh& rebuilt, const MedialComplex& mc,
                          long long uniform_samples = 0) {
  evaluation::ReconstructionStage stage;
  ParamSet params;
  params.set("surface_samples", uniform_samples);
  stage.configure(params);
  BasicContext ctx(1);
  ctx.data().publish(kReconstructedSurface, ReconstructedSurface{rebuilt, Similarity{}, "test"}, "msd");
  return stage.evaluate(shape, mc, ctx);
}

/// Distance from a point outside (or on) the box [−a, a]³ to the box.
double distance_to_box(const Vec3& p, double a) {
  return (p.cwiseAbs().array() - a).cwiseMax(0.0).matrix().norm();
}

}  // namespace

TEST_CASE("reconstruction: a rebuilt sphere inside an icosphere shape gives the radius gap", "[reconstruction][rebuilt]") {
  Shape shape;
  shape.mesh = testing::make_sphere(1.0, 4);
  const SurfaceMesh rebuilt = testing::make_sphere(0.8, 4);  // the same tessellation, scaled
  const double sag = test::icosphere_sag(shape.mesh, 1.0);
  const Metrics m = measure_published(shape, rebuilt, test::one_sphere(0.3));  // the complex is not measured
  // A shape vertex v (|v| = 1) is 0.2 from the rebuilt vertex 0.8·v, and the rebuilt surface lies
  // in the ball of radius 0.8: exactly 0.2.
  CHECK(m.at("surface_to_rebuilt_max") == Approx(0.2).margin(1e-12));
  CHECK(m.at("surface_to_rebuilt_mean") == Approx(0.2).margin(1e-12));
  // A rebuilt vertex 0.8·v is inside the shape, whose faces are between 1 − sag and 1 from the centre.
  CHECK(m.at("rebuilt_to_surface_max") <= 0.2 + 1e-12);
  CHECK(m.at("rebuilt_to_surface_mean") >= 0.2 - sag - 1e-12);
  CHECK(m.at("eps1") == m.at("surface_to_rebuilt_mean"));
  CHECK(m.at("eps2") == m.at("rebuilt_to_surface_mean"));
  CHECK(m.at("eps") == std::max(m.at("eps1"), m.at("eps2")));
  CHECK(m.at("hausdorff") == Approx(0.2).margin(1e-12));
  CHECK(m.at("hausdorff_pct") == Approx(100 * 0.2 / m.at("bbox_diagonal")));
  CHECK(m.at("surface_samples") == shape.mesh.vertices.size());
  CHECK(m.at("rebuilt_samples") == rebuilt.vertices.size());
  CHECK(m.at("rebuilt_area") == Approx(4 * M_PI * 0.64).epsilon(0.01));
  CHECK(m.count("envelope_samples") == 0);  // the envelope was not measured
}

TEST_CASE("reconstruction: a box rebuilt 0.1 larger gives the analytic box distances", "[reconstruction][rebuilt]") {
  Shape shape;
  shape.mesh = testing::make_box(1.0, 1.0, 1.0, 4);
  const SurfaceMesh rebuilt = testing::make_box(1.1, 1.1, 1.1, 4);
  // Every point of the inner box's surface is 0.1 from the outer box's nearest face; a rebuilt
  // vertex is at its distance to the box [−1, 1]³, √3·0.1 at the corners.
  double expected_mean = 0, expected_max = 0;
  for (const Vec3& v : rebuilt.vertices) {
    expected_mean += distance_to_box(v, 1.0) / static_cast<double>(rebuilt.vertices.size());
    expected_max = std::max(expected_max, distance_to_box(v, 1.0));
  }
  REQUIRE(expected_max == Approx(0.1 * std::sqrt(3.0)));
  SECTION("at the vertices") {
    const Metrics m = measure_published(shape, rebuilt, test::one_sphere(0.5));
    CHECK(m.at("surface_to_rebuilt_max") == Approx(0.1).margin(1e-12));
    CHECK(m.at("surface_to_rebuilt_mean") == Approx(0.1).margin(1e-12));
    CHECK(m.at("rebuilt_to_surface_max") == Approx(expected_max).margin(1e-12));
    CHECK(m.at("rebuilt_to_surface_mean") == Approx(expected_mean).margin(1e-12));
    CHECK(m.at("hausdorff") == Approx(0.1 * std::sqrt(3.0)).margin(1e-12));
    CHECK(m.at("eps") == Approx(std::max(0.1, expected_mean)).margin(1e-12));
    CHECK(m.at("rebuilt_area") == Approx(6 * 2.2 * 2.2));
  }
  SECTION("with area-uniform samples on both sides") {
    const Metrics m = measure_published(shape, rebuilt, test::one_sphere(0.5), 4000);
    CHECK(m.at("surface_samples") == shape.mesh.vertices.size() + 4000);
    CHECK(m.at("rebuilt_samples") == rebuilt.vertices.size() + 4000);
    CHECK(m.at("surface_to_rebuilt_max") == Approx(0.1).margin(1e-12));
    CHECK(m.at("surface_to_rebuilt_mean") == Approx(0.1).margin(1e-12));
    // Face samples are 0.1 from the inner box, edge and corner regions up to √3·0.1.
    CHECK(m.at("rebuilt_to_surface_max") == Approx(expected_max).margin(1e-12));
    CHECK(m.at("rebuilt_to_surface_mean") > 0.1);
    CHECK(m.at("rebuilt_to_surface_mean") < expected_mean);
  }
}

TEST_CASE("reconstruction: a rebuilt surface without faces is refused", "[reconstruction][rebuilt]") {
  Shape shape;
  shape.mesh = testing::make_sphere(1.0, 2);
  CHECK_THROWS_WITH(measure_published(shape, SurfaceMesh{}, test::one_sphere(1.0)), Catch::Contains("no faces"));
}

TEST_CASE("counts: a published representation size replaces N_d and N_c", "[counts]") {
  MedialComplex mc;
  for (int v = 0; v < 3; ++v) mc.add_vertex(Vec3(v, 0, 0), 0.1);
  mc.add_edge(0, 1);
  mc.add_edge(1, 2);
  evaluation::CountsStage stage;
  BasicContext ctx(1);
  const Metrics plain = stage.evaluate(Shape{}, mc, ctx);
  CHECK(plain.at("N_d") == 3 + 2);
  CHECK(plain.at("N_c") == 4 * 3);
  ctx.data().publish(kRepresentationSize, RepresentationSize{5, 3 * 3 + 120, "MSD: N_c = Σ|V(T_P)| + 3·#v"}, "msd");
  const Metrics m = stage.evaluate(Shape{}, mc, ctx);
  CHECK(m.at("N_d") == 5);
  CHECK(m.at("N_c") == 129);
  CHECK(m.at("vertices") == 3);  // the complex's own counts stay
  CHECK(m.at("unique_edges") == 2);
}
