// Shrinking-ball medial spheres (Ma et al. 2012) on analytic shapes with known medial axes.
#include <medax/services/sampling.hpp>
#include <medax/services/shrinking_ball.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace medax;

TEST_CASE("Shrinking balls of a sphere's vertices: centre at the origin, radius R", "[geometry][shrinking_ball]") {
  const double R = 2.0;
  const SurfaceMesh sphere = testing::make_sphere(R, 4);
  const services::PointIndex index(sphere.vertices);
  services::ShrinkingBallOptions options;
  options.initial_radius = 4 * R;  // at least the bbox diagonal: the ball only shrinks
  SECTION("exact normals: the ball through p and any other point is the sphere itself") {
    std::vector<Vec3> normals;
    for (const Vec3& p : sphere.vertices) normals.push_back(p.normalized());
    const auto balls = services::shrinking_balls(index, sphere.vertices, normals, options);
    REQUIRE(balls.size() == sphere.vertices.size());
    for (std::size_t i = 0; i < balls.size(); ++i) {
      CHECK(balls[i].centre.norm() < 1e-9 * R);
      CHECK(balls[i].radius == Approx(R).epsilon(1e-9));
      CHECK(balls[i].contact != i);
      if (i % 97 == 0) {  // the single-point version gives the same ball
        const auto one = services::shrinking_ball(index, sphere.vertices[i], normals[i], options);
        CHECK(one.centre == balls[i].centre);
        CHECK(one.radius == balls[i].radius);
      }
    }
  }
  SECTION("area-weighted vertex normals: close, the normals being slightly off radial") {
    const OrientedSamples s = services::vertex_samples(sphere);
    const auto balls = services::shrinking_balls(index, s.points, s.normals, options);
    for (const auto& b : balls) {
      CHECK(b.centre.norm() < 0.05 * R);
      CHECK(b.radius == Approx(R).epsilon(0.05));
    }
  }
}

TEST_CASE("Shrinking balls of a capsule: centres on the core segment, radius the capsule's",
          "[geometry][shrinking_ball]") {
  const double radius = 0.5, half_length = 1.0;
  const SurfaceMesh capsule = testing::make_capsule(radius, half_length, 48);
  // The capsule's exact outward normals: away from the closest point of the core segment.
  std::vector<Vec3> normals;
  for (const Vec3& p : capsule.vertices)
    normals.push_back((p - Vec3(0, 0, std::clamp(p.z(), -half_length, half_length))).normalized());
  const services::PointIndex index(capsule.vertices);
  services::ShrinkingBallOptions options;
  options.initial_radius = 2 * (half_length + radius) * 2;
  const auto balls = services::shrinking_balls(index, capsule.vertices, normals, options);
  std::vector<double> axis, radius_error;
  for (const auto& b : balls) {
    axis.push_back(testing::capsule_axis_distance(b.centre, half_length));
    radius_error.push_back(std::abs(b.radius - radius));
  }
  std::sort(axis.begin(), axis.end());
  std::sort(radius_error.begin(), radius_error.end());
  // Every centre near the core segment, the bulk very near (the mesh's vertices are on the
  // capsule, but the balls are stopped by vertices, not by the smooth surface).
  CHECK(axis[axis.size() / 2] < 0.01 * radius);
  CHECK(axis[axis.size() * 95 / 100] < 0.05 * radius);
  CHECK(axis.back() < 0.1 * radius);
  CHECK(radius_error[radius_error.size() / 2] < 0.01 * radius);
  CHECK(radius_error[radius_error.size() * 95 / 100] < 0.05 * radius);
  CHECK(radius_error.back() < 0.1 * radius);
}
