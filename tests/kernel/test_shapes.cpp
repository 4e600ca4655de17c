// The SDK's analytic fixtures: each mesh is closed, consistently outward oriented, has the
// right Euler characteristic and volume, and its vertices lie on the analytic surface.
#include <medax/testing/shapes.hpp>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <map>
#include <set>

using namespace medax;
using namespace medax::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Topology {
  bool closed = true;       ///< every undirected edge in exactly two faces
  bool consistent = true;   ///< every directed edge once (neighbours traverse it oppositely)
  bool degenerate = false;  ///< a face repeats a vertex
  long euler = 0;
  std::size_t unused_vertices = 0;
};

Topology topology(const SurfaceMesh& m) {
  Topology t;
  std::map<std::pair<Index, Index>, int> undirected, directed;
  std::set<Index> used;
  for (const Tri& f : m.faces) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) t.degenerate = true;
    for (int k = 0; k < 3; ++k) {
      const Index a = f[k], b = f[(k + 1) % 3];
      ++directed[{a, b}];
      ++undirected[{std::min(a, b), std::max(a, b)}];
      used.insert(a);
    }
  }
  for (const auto& [edge, count] : undirected) t.closed = t.closed && count == 2;
  for (const auto& [edge, count] : directed) t.consistent = t.consistent && count == 1;
  t.unused_vertices = m.vertices.size() - used.size();
  t.euler = static_cast<long>(m.vertices.size()) - static_cast<long>(undirected.size()) +
            static_cast<long>(m.faces.size());
  return t;
}

/// Positive for a closed mesh whose faces turn counter-clockwise seen from outside.
double signed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (const Tri& f : m.faces) v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

struct Case {
  const char* name;
  SurfaceMesh mesh;
  long euler;
  double volume;               ///< of the analytic shape
  double volume_tolerance;     ///< relative (the mesh only approximates curved surfaces)
  std::function<double(const Vec3&)> surface_error;  ///< 0 on the analytic surface
};

std::vector<Case> cases() {
  const double a = 2, b = 1.2, c = 0.7;
  return {
      {"sphere", make_sphere(1.5, 3), 2, 4.0 / 3.0 * kPi * std::pow(1.5, 3), 0.02,
       [](const Vec3& p) { return p.norm() - 1.5; }},
      {"ellipsoid", make_ellipsoid(a, b, c, 3), 2, 4.0 / 3.0 * kPi * a * b * c, 0.02,
       [=](const Vec3& p) { return std::pow(p.x() / a, 2) + std::pow(p.y() / b, 2) + std::pow(p.z() / c, 2) - 1; }},
      {"capsule", make_capsule(0.5, 1.0, 48), 2, kPi * 0.25 * 2.0 + 4.0 / 3.0 * kPi * 0.125, 0.02,
       [](const Vec3& p) { return capsule_axis_distance(p, 1.0) - 0.5; }},
      {"cylinder", make_cylinder(0.8, 1.5, 48), 2, kPi * 0.64 * 3.0, 0.01,
       [](const Vec3& p) {
         const double rho = std::hypot(p.x(), p.y());
         if (std::abs(std::abs(p.z()) - 1.5) < 1e-12) return std::max(0.0, rho - 0.8);  // on a cap
         return std::abs(rho - 0.8) + std::max(0.0, std::abs(p.z()) - 1.5);             // on the side
       }},
      {"torus", make_torus(2.0, 0.5, 64, 32), 0, 2 * kPi * kPi * 2.0 * 0.25, 0.02,
       [](const Vec3& p) { return torus_axis_distance(p, 2.0) - 0.5; }},
      {"box", make_box(1.0, 0.5, 2.0, 4), 2, 8 * 1.0 * 0.5 * 2.0, 1e-12,
       [](const Vec3& p) { return std::max({std::abs(p.x()) / 1.0, std::abs(p.y()) / 0.5, std::abs(p.z()) / 2.0}) - 1; }},
  };
}

}  // namespace

TEST_CASE("analytic fixture meshes are closed and oriented outward and have the right Euler characteristic",
          "[testing][shapes]") {
  for (const Case& c : cases()) {
    INFO(c.name);
    const Topology t = topology(c.mesh);
    CHECK_FALSE(c.mesh.faces.empty());
    CHECK_FALSE(t.degenerate);
    CHECK(t.unused_vertices == 0);
    CHECK(t.closed);
    CHECK(t.consistent);
    CHECK(t.euler == c.euler);
    const double volume = signed_volume(c.mesh);
    CHECK(volume > 0);
    CHECK(volume == Approx(c.volume).epsilon(c.volume_tolerance));
  }
}

TEST_CASE("analytic fixture vertices lie on the analytic surface", "[testing][shapes]") {
  for (const Case& c : cases()) {
    INFO(c.name);
    double worst = 0;
    for (const Vec3& v : c.mesh.vertices) worst = std::max(worst, std::abs(c.surface_error(v)));
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("icosphere face counts follow the subdivision level", "[testing][shapes]") {
  CHECK(make_sphere(1, 0).faces.size() == 20);
  CHECK(make_sphere(1, 2).faces.size() == 320);
  CHECK(make_sphere(1, 2).vertices.size() == 162);
}

TEST_CASE("exact medial axis distances", "[testing][shapes]") {
  CHECK(sphere_axis_distance(Vec3(3, 4, 0)) == 5.0);
  CHECK(capsule_axis_distance(Vec3(0.3, 0.4, 0.5), 1.0) == Approx(0.5));  // beside the segment
  CHECK(capsule_axis_distance(Vec3(0, 0, 3), 1.0) == Approx(2.0));        // beyond its end
  CHECK(torus_axis_distance(Vec3(2, 0, 0.5), 2.0) == Approx(0.5));
  CHECK(torus_axis_distance(Vec3(0, 0, 0), 2.0) == Approx(2.0));
  // Ellipsoid a > b > c: the medial sheet is z = 0 inside x²/A² + y²/B² ≤ 1.
  const double a = 3, b = 2, c = 1, A = (a * a - c * c) / a;
  CHECK(ellipsoid_axis_distance(Vec3(0.5, 0.2, 0.3), a, b, c) == Approx(0.3));
  CHECK(ellipsoid_axis_distance(Vec3(A + 0.4, 0, 0), a, b, c) == Approx(0.4).margin(1e-9));
  CHECK(ellipsoid_axis_distance(Vec3(A + 0.3, 0, 0.4), a, b, c) == Approx(0.5).margin(1e-9));
}
