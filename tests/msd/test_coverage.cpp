// MSD coverage E_cov (paper Eq. 8; notes §7 items 6, 7) with fitted primitives on analytic shapes.
#include "coverage.hpp"
#include "fitting.hpp"

#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

using namespace medax;
using namespace medax::msd;

namespace {

SkeletonElement vertex_at(const Vec3& p) { return {ElementKind::Vertex, {0, 0, 0}, {p, p, p}}; }

/// δ that absorbs the chord error of T_P between its vertices on a curved S: the template's
/// angular step θ ≈ √(4π/1588) ≈ 0.089 gives a sagitta of R θ²/8 ≈ 1e-3 R.
constexpr double kChordDelta = 3e-3;

}  // namespace

TEST_CASE("msd coverage: one vertex primitive covers a sphere, one edge primitive a capsule") {
  CoverageOptions options;
  options.delta = kChordDelta;
  for (const CoverageTest test : {CoverageTest::Radial, CoverageTest::SignedDistance}) {
    options.test = test;
    const TargetMesh sphere(medax::testing::make_sphere(1.0, 4));
    const Coverage on_sphere = coverage(sphere, {fit_primitive(sphere, vertex_at(Vec3::Zero()))}, options);
    CHECK(on_sphere.energy == Approx(-1.0).margin(1e-12));
    const TargetMesh capsule(medax::testing::make_capsule(0.3, 1.0, 64));
    const SkeletonElement axis{ElementKind::Edge, {0, 1, 0}, {Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, 0, 1)}};
    const Coverage on_capsule = coverage(capsule, {fit_primitive(capsule, axis)}, options);
    CHECK(on_capsule.energy == Approx(-1.0).margin(1e-12));
  }
}

TEST_CASE("msd coverage: E_cov in [-1, 0], monotone under added primitives, both tests agree away from T_P") {
  const TargetMesh box(medax::testing::make_box(1.0, 0.5, 0.5, 10));
  std::vector<Primitive> primitives{fit_primitive(box, vertex_at({-0.6, 0, 0}))};
  const Coverage one = coverage(box, primitives);
  primitives.push_back(fit_primitive(box, vertex_at({0.6, 0.1, 0})));
  const Coverage two = coverage(box, primitives);
  const SkeletonElement middle{ElementKind::Edge, {0, 1, 0}, {Vec3(-0.3, 0, 0), Vec3(0.3, 0, 0), Vec3(0.3, 0, 0)}};
  primitives.push_back(fit_primitive(box, middle));
  const Coverage three = coverage(box, primitives);
  for (const Coverage* c : {&one, &two, &three}) {
    CHECK(c->energy >= -1.0 - 1e-12);
    CHECK(c->energy <= 0.0);
  }
  CHECK(one.energy < 0);          // a sphere in a box touches some of the box
  CHECK(two.energy < one.energy);  // the second sphere covers the other end
  std::size_t lost = 0;
  for (std::size_t v = 0; v < one.covered.size(); ++v) lost += (one.covered[v] && !two.covered[v]) + (two.covered[v] && !three.covered[v]);
  CHECK(lost == 0);
  CHECK(three.energy <= two.energy);
  // No primitive: nothing covered.
  CHECK(coverage(box, {}).energy == 0.0);
  // The radial value and the signed distance have the same sign away from the surface of T_P.
  const PrimitiveShape shape(primitives[0]);
  for (const Vec3& x : {Vec3(-0.6, 0.01, 0.02), Vec3(-0.2, 0.05, 0), Vec3(0.9, 0.4, 0.4), Vec3(-0.6, 0.0, 2.0)}) {
    const double radial = shape.radial(x), distance = shape.signed_distance(x);
    if (std::abs(distance) > 1e-3) CHECK((radial < 0) == (distance < 0));
  }
}
