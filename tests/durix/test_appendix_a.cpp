// Appendix A of the paper (notes §3.9): balls centred outside the shape. A coarse, flat
// ellipsoid has interior Delaunay cells at its surface whose circumcentres lie outside it.
#include "fixtures.hpp"

#include <medax/services/inside.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

using namespace medax;
using namespace medax::durix;

namespace {

struct Run {
  DurixResult result;
  std::size_t outside = 0;  ///< output nodes centred outside the input (independent inside test)
};

Run run(const SurfaceMesh& mesh, double relative_eps, bool remove_outside_centres) {
  DurixOptions options;
  options.remove_outside_centres = remove_outside_centres;
  const EpsilonOracle oracle(relative_eps * bbox_diagonal(mesh.vertices));
  Run r{durix_medial_axis(mesh, oracle, options)};
  const services::InsideTest inside(mesh);
  for (const Vec3& c : r.result.medial.centres) r.outside += !inside.inside(c);
  return r;
}

}  // namespace

TEST_CASE("durix: cells centred outside the shape are carved when epsilon allows (Appendix A)", "[durix][appendix_a]") {
  const SurfaceMesh mesh = durix::test::to_delaunay(testing::make_ellipsoid(1.5, 1.0, 0.25, 2));
  const double eps = 0.01;

  const Run kept = run(mesh, eps, false);
  const Run removed = run(mesh, eps, true);
  // Boundary simplification alone leaves some outside balls on this shape; the removal leaves none.
  REQUIRE(kept.outside > 0);
  CHECK(kept.result.report.outside_centres_left == kept.outside);
  CHECK(removed.result.report.outside_centres_removed > 0);
  CHECK(removed.outside == 0);
  CHECK(removed.result.report.outside_centres_left == 0);
  // The carving is an ordinary ε-tested, validated carving: every invariant of notes §5 holds.
  durix::test::check_invariants(mesh, removed.result, eps * bbox_diagonal(mesh.vertices));
}

TEST_CASE("durix: epsilon 0 keeps the outside balls (Fig. 16)", "[durix][appendix_a]") {
  const SurfaceMesh mesh = durix::test::to_delaunay(testing::make_ellipsoid(1.5, 1.0, 0.25, 2));
  const Run raw = run(mesh, 0.0, true);
  CHECK(raw.result.report.outside_centres_removed == 0);
  CHECK(raw.outside > 0);
  CHECK(raw.result.report.outside_centres_left == raw.outside);
}
