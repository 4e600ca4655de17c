// services::RayParityInside, the exact batch inside test of the voronoi and dey_zhao
// extractions: the same answers as CGAL's Side_of_triangle_mesh on every good Debian-corpus mesh, and
// the analytic answer on a box queried on a lattice that sends rays through its edges and
// vertices and puts points on its faces.
#include <medax/io.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/ray_parity.hpp>
#include <medax/testing/shapes.hpp>

#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <random>

using namespace medax;
using services::RayParityInside;

namespace {

}  // namespace

TEST_CASE("RayParityInside agrees with Side_of_triangle_mesh on every good mesh of the Debian corpus",
          "[geometry][inside]") {
  const auto meshes = test::debian_corpus(false);
  CHECK(meshes.size() == 12);
  for (const auto& path : meshes) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    const RayParityInside fast(mesh);
    const services::InsideTest reference(mesh);
    Vec3 lo = mesh.vertices.front(), hi = lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    std::mt19937_64 rng(2024);
    const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    std::vector<Vec3> points;
    for (int i = 0; i < 2000; ++i) points.push_back(lo - 0.1 * (hi - lo) + Vec3(u(), u(), u()).cwiseProduct(1.2 * (hi - lo)));
    // Points on the surface (the vertices: outside for both) and just off it on either side.
    for (std::size_t k = 0; k < mesh.vertices.size(); k += std::max<std::size_t>(1, mesh.vertices.size() / 500))
      points.push_back(mesh.vertices[k]);
    for (std::size_t k = 0; k < mesh.faces.size(); k += std::max<std::size_t>(1, mesh.faces.size() / 500)) {
      const Tri& f = mesh.faces[k];
      const Vec3 a = mesh.vertices[f[0]], b = mesh.vertices[f[1]], c = mesh.vertices[f[2]];
      const Vec3 n = (b - a).cross(c - a);
      const double scale = std::sqrt(n.norm());
      points.push_back((a + b + c) / 3 + 1e-3 * scale * n.normalized());
      points.push_back((a + b + c) / 3 - 1e-3 * scale * n.normalized());
    }
    const std::vector<char> got = fast.inside(points), sequential = fast.inside(points, false);
    const std::vector<char> want = reference.inside(points);
    std::size_t disagree = 0, inside = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      disagree += got[i] != want[i];
      inside += want[i];
      if (i % 50 == 0) CHECK(fast.inside(points[i]) == static_cast<bool>(want[i]));
    }
    CHECK(disagree == 0);
    CHECK(got == sequential);
    CHECK(inside > 0);
    for (std::size_t k = 0; k < mesh.vertices.size(); k += 97) CHECK_FALSE(fast.inside(mesh.vertices[k]));
  }
}

TEST_CASE("RayParityInside on a box lattice: rays through edges and vertices, points on faces",
          "[geometry][inside]") {
  const Vec3 a(1.0, 0.5, 0.25);
  const SurfaceMesh box = testing::make_box(a.x(), a.y(), a.z(), 4);
  const RayParityInside fast(box);
  const services::InsideTest reference(box);
  // Steps of a/16 hit the box's faces, its grid lines (spacing a/2) and its vertices exactly.
  std::vector<Vec3> points;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j)
      for (int k = -20; k <= 20; ++k) points.emplace_back(i / 16.0, j / 32.0, k / 64.0);
  const std::vector<char> got = fast.inside(points);
  std::size_t inside = 0, on_surface = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 q = points[i].cwiseAbs();
    const bool truth = q.x() < a.x() && q.y() < a.y() && q.z() < a.z();
    on_surface += (q - a).maxCoeff() == 0;
    INFO("point " << points[i].transpose());
    CHECK(static_cast<bool>(got[i]) == truth);
    CHECK(reference.inside(points[i]) == truth);
    inside += truth;
  }
  CHECK(inside > 1000);
  CHECK(on_surface > 100);
}

TEST_CASE("RayParityInside ignores face orientation and accepts seams of coincident vertices",
          "[geometry][inside]") {
  // A cube whose six faces have their own vertices (closed by positions, not by indices),
  // half of its faces turned inside out.
  SurfaceMesh cube;
  const SurfaceMesh shared = testing::make_box(1, 1, 1, 1);
  for (std::size_t f = 0; f < shared.faces.size(); ++f) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
      t[k] = static_cast<Index>(cube.vertices.size());
      cube.vertices.push_back(shared.vertices[shared.faces[f][k]]);
    }
    if (f % 2) std::swap(t[1], t[2]);
    cube.faces.push_back(t);
  }
  const RayParityInside test(cube);
  CHECK(test.inside(Vec3(0, 0, 0)));
  CHECK(test.inside(Vec3(0.9, -0.9, 0.3)));
  CHECK_FALSE(test.inside(Vec3(1.1, 0, 0)));
  CHECK_FALSE(test.inside(Vec3(1.0, 0, 0)));
  CHECK_FALSE(test.inside(Vec3(0, 0, -2)));
}

TEST_CASE("RayParityInside refuses an open mesh", "[geometry][inside]") {
  SurfaceMesh sphere = testing::make_sphere(1.0, 2);
  sphere.faces.pop_back();
  CHECK_THROWS_AS(RayParityInside(sphere), std::invalid_argument);
  CHECK_THROWS_AS(RayParityInside(SurfaceMesh{}), std::invalid_argument);
}
