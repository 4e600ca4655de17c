// SurfaceDistance (AABB closest points) against the analytic distance to a sphere and against
// brute force over the faces of a box.
#include <medax/services/closest_point.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace medax;

namespace {

/// Exact distance from p to the triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

std::vector<Vec3> random_points(std::size_t n, double half, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<Vec3> out(n);
  for (Vec3& p : out) p = Vec3(2 * u() - 1, 2 * u() - 1, 2 * u() - 1) * half;
  return out;
}

}  // namespace

TEST_CASE("SurfaceDistance to an icosphere matches | |p| - r | up to the chordal error", "[geometry][closest]") {
  const double r = 1.5;
  const SurfaceMesh sphere = testing::make_sphere(r, 4);
  const services::SurfaceDistance distance(sphere);
  // Chordal error of a level-4 icosphere: the face centres are r (1 - cos θ) inside, θ being the
  // angle of a face's circumradius, below 0.3% of r here.
  const double chord = 0.003 * r;
  const auto points = random_points(300, 3.0, 5);
  const std::vector<double> batch = distance.distances(points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const auto cp = distance.closest(p);
    CHECK(cp.distance == Approx(std::abs(p.norm() - r)).margin(chord));
    CHECK(batch[i] == cp.distance);
    CHECK((cp.point - p).norm() == Approx(cp.distance).margin(1e-12));
    // The closest point lies on the face it names, between the two spheres r(1 - chord) and r.
    REQUIRE(cp.face < sphere.faces.size());
    const auto& f = sphere.faces[cp.face];
    const Vec3 on_face = closest_on_triangle(cp.point, sphere.vertices[f[0]], sphere.vertices[f[1]],
                                             sphere.vertices[f[2]]);
    CHECK((on_face - cp.point).norm() < 1e-12);
    CHECK(cp.point.norm() <= r + 1e-12);
    CHECK(cp.point.norm() >= r - chord);
  }
}

TEST_CASE("SurfaceDistance matches brute force over every face of a box", "[geometry][closest]") {
  const SurfaceMesh box = testing::make_box(1.0, 0.5, 0.25, 4);
  const services::SurfaceDistance distance(box);
  for (const Vec3& p : random_points(200, 1.5, 17)) {
    double best = INFINITY;
    for (const Tri& f : box.faces)
      best = std::min(best, (closest_on_triangle(p, box.vertices[f[0]], box.vertices[f[1]], box.vertices[f[2]]) - p).norm());
    CHECK(distance.distance(p) == Approx(best).margin(1e-12));
    // And the box's analytic distance, inside or outside.
    const Vec3 q = p.cwiseAbs() - Vec3(1.0, 0.5, 0.25);
    const double analytic = q.maxCoeff() > 0 ? q.cwiseMax(0.0).norm() : -q.maxCoeff();
    CHECK(distance.distance(p) == Approx(analytic).margin(1e-12));
  }
}
