// Sampling services: face normals and areas, vertex samples, uniform samples.
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace medax;

namespace {
/// Distance from p to the surface of the box [-a, a] (inside or outside).
double box_surface_distance(const Vec3& p, const Vec3& a) {
  const Vec3 q = p.cwiseAbs() - a;
  return q.maxCoeff() > 0 ? q.cwiseMax(0.0).norm() : -q.maxCoeff();
}
}  // namespace

TEST_CASE("Face normals point outward and areas sum to the box's surface", "[geometry][sampling]") {
  const Vec3 a(1.0, 0.5, 0.25);
  const SurfaceMesh box = testing::make_box(a.x(), a.y(), a.z(), 3);
  const auto normals = services::face_normals(box);
  const auto areas = services::face_areas(box);
  REQUIRE(normals.size() == box.faces.size());
  for (std::size_t f = 0; f < box.faces.size(); ++f) {
    const Vec3 centre = (box.vertices[box.faces[f][0]] + box.vertices[box.faces[f][1]] + box.vertices[box.faces[f][2]]) / 3;
    CHECK(normals[f].norm() == Approx(1.0));
    // Outward: the normal is the axis of the face the centre lies on.
    int axis = 0;
    (centre.cwiseAbs() - a).maxCoeff(&axis);
    CHECK(std::abs(normals[f][axis]) == Approx(1.0));
    CHECK(normals[f][axis] * centre[axis] > 0);
    CHECK(areas[f] > 0);
  }
  const double total = 8 * (a.x() * a.y() + a.y() * a.z() + a.z() * a.x());
  CHECK(services::surface_area(box) == Approx(total).epsilon(1e-12));
}

TEST_CASE("Vertex samples carry a third of their faces' areas and outward normals", "[geometry][sampling]") {
  const SurfaceMesh sphere = testing::make_sphere(1.0, 3);
  const OrientedSamples s = services::vertex_samples(sphere);
  REQUIRE(s.size() == sphere.vertices.size());
  double area = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    CHECK(s.points[i] == sphere.vertices[i]);
    CHECK(s.normals[i].norm() == Approx(1.0));
    CHECK(s.normals[i].dot(s.points[i].normalized()) > 0.999);
    area += s.areas[i];
  }
  CHECK(area == Approx(services::surface_area(sphere)).epsilon(1e-12));
}

TEST_CASE("Uniform samples lie on the surface, with face normals, and depend only on the seed",
          "[geometry][sampling]") {
  const Vec3 a(1.0, 0.5, 0.25);
  const SurfaceMesh box = testing::make_box(a.x(), a.y(), a.z(), 2);
  std::mt19937_64 rng(42), rng_again(42), rng_other(43);
  const OrientedSamples s = services::sample_uniform(box, 2000, rng);
  REQUIRE(s.size() == 2000);
  double area = 0;
  std::array<int, 3> per_axis{};
  for (std::size_t i = 0; i < s.size(); ++i) {
    CHECK(std::abs(box_surface_distance(s.points[i], a)) < 1e-12);
    int axis = 0;
    s.normals[i].cwiseAbs().maxCoeff(&axis);
    CHECK(std::abs(s.normals[i][axis]) == Approx(1.0));
    CHECK(s.normals[i][axis] * s.points[i][axis] > 0);
    ++per_axis[axis];
    area += s.areas[i];
  }
  CHECK(area == Approx(services::surface_area(box)).epsilon(1e-12));
  // By area: the two x faces hold 2·(2·0.5·2·0.25)... = 1/7 of the surface, y 2/7, z 4/7.
  CHECK(per_axis[0] == Approx(2000.0 / 7).margin(60));
  CHECK(per_axis[1] == Approx(4000.0 / 7).margin(80));
  CHECK(per_axis[2] == Approx(8000.0 / 7).margin(80));
  const OrientedSamples again = services::sample_uniform(box, 2000, rng_again);
  CHECK(again.points == s.points);
  CHECK(services::sample_uniform(box, 2000, rng_other).points != s.points);
  SurfaceMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.faces = {{0, 1, 2}};
  CHECK_THROWS_AS(services::sample_uniform(flat, 10, rng), std::invalid_argument);
}
