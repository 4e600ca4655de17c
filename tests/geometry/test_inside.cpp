// Inside tests: CGAL Side_of_triangle_mesh (InsideTest) against the generalized winding number
// on every good mesh of the Debian corpus, and against the analytic answer on a sphere.
#include <medax/io.hpp>
#include <medax/services/inside.hpp>
#include <medax/testing/shapes.hpp>

#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <random>

using namespace medax;

namespace {

/// Uniform points in the mesh's bounding box grown by 10% on each side.
std::vector<Vec3> points_around(const SurfaceMesh& mesh, std::size_t n, std::uint64_t seed) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const Vec3 margin = 0.1 * (hi - lo);
  lo -= margin, hi += margin;
  std::mt19937_64 rng(seed);
  const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<Vec3> out(n);
  for (Vec3& p : out) p = lo + Vec3(u(), u(), u()).cwiseProduct(hi - lo);
  return out;
}

}  // namespace

TEST_CASE("InsideTest agrees with the winding number on every good mesh of the Debian corpus", "[geometry][inside]") {
  const auto meshes = test::debian_corpus(false);
  CHECK(meshes.size() == 12);
  for (const auto& path : meshes) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    const services::InsideTest test(mesh);
    // 200 points per mesh; the winding number costs O(#faces) per point, so fewer on the
    // larger meshes (at most 1.5M triangle visits, at least 20 points) to keep the test quick.
    const std::size_t n = std::clamp<std::size_t>(1500000 / mesh.faces.size(), 20, 200);
    auto points = points_around(mesh, n, 12345);
    // Thin shapes are rarely hit by random points: add points just inside and just outside
    // the surface, a tenth of the mean edge length along the face normals from face centres.
    double edge = 0;
    for (const Tri& f : mesh.faces) edge += (mesh.vertices[f[1]] - mesh.vertices[f[0]]).norm();
    edge /= static_cast<double>(mesh.faces.size());
    for (std::size_t k = 0; k < 8; ++k) {
      const Tri& f = mesh.faces[k * mesh.faces.size() / 8];
      const Vec3 a = mesh.vertices[f[0]], b = mesh.vertices[f[1]], c = mesh.vertices[f[2]];
      const Vec3 n = (b - a).cross(c - a).normalized();
      points.push_back((a + b + c) / 3 - 0.1 * edge * n);
      points.push_back((a + b + c) / 3 + 0.1 * edge * n);
    }
    const std::vector<char> batch = test.inside(points);
    std::size_t inside = 0, disagree = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double w = services::winding_number(mesh, points[i]);
      // A closed mesh's winding number is 0 or ±1 (±: orientation) away from the surface.
      CHECK((std::abs(w) < 1e-6 || std::abs(std::abs(w) - 1) < 1e-6));
      const bool by_winding = std::abs(w) > 0.5;
      if (by_winding != static_cast<bool>(batch[i])) ++disagree;
      CHECK(test.inside(points[i]) == static_cast<bool>(batch[i]));
      inside += by_winding;
    }
    CHECK(disagree == 0);
    CHECK(inside > 0);            // the sample reaches the inside ...
    CHECK(inside < points.size());  // ... and the outside
  }
}

TEST_CASE("InsideTest and the winding number on an icosphere match |p| < r away from the surface",
          "[geometry][inside]") {
  const SurfaceMesh sphere = testing::make_sphere(2.0, 3);
  const services::InsideTest test(sphere);
  // The icosphere lies between the radius r cos(θ) (face centres) and r; stay clear of that band.
  const auto points = points_around(sphere, 500, 99);
  std::size_t checked = 0;
  for (const Vec3& p : points) {
    const double r = p.norm();
    if (r > 1.9 && r < 2.05) continue;
    ++checked;
    CHECK(test.inside(p) == (r < 2.0));
    CHECK(services::winding_number(sphere, p) == Approx(r < 2.0 ? 1.0 : 0.0).margin(1e-9));
  }
  CHECK(checked > 400);
  // Vertices are on the surface: not strictly inside.
  for (const Vec3& v : sphere.vertices) CHECK_FALSE(test.inside(v));
}

TEST_CASE("InsideTest refuses a non-manifold mesh", "[geometry][inside]") {
  SurfaceMesh m = testing::make_sphere(1.0, 1);
  m.faces.push_back(m.faces.front());  // a third face on three edges
  CHECK_THROWS_AS(services::InsideTest(m), std::invalid_argument);
}
