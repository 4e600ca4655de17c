// Topology service: Euler characteristic and Betti numbers over Z/2 of small complexes with a
// known answer, and of surface meshes.
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

using namespace medax;
using services::complex_topology;

namespace {

void check_betti(const services::ComplexTopology& t, std::size_t b0, std::size_t b1, std::size_t b2) {
  CHECK(t.b0 == b0);
  CHECK(t.b1 == b1);
  CHECK(t.b2 == b2);
  CHECK(t.euler == static_cast<long long>(b0) - static_cast<long long>(b1) + static_cast<long long>(b2));
}

/// A triangulated annulus: `n` quads around a circle, each split in two.
std::vector<Tri> annulus(Index n) {
  std::vector<Tri> faces;
  for (Index i = 0; i < n; ++i) {
    const Index a = i, b = (i + 1) % n, c = n + i, d = n + (i + 1) % n;
    faces.push_back({a, b, d});
    faces.push_back({a, d, c});
  }
  return faces;
}

}  // namespace

TEST_CASE("topology: a triangle is a disk: chi = 1, b1 = 0", "[topology]") {
  const auto t = complex_topology(3, {}, {{0, 1, 2}});
  CHECK(t.vertices == 3);
  CHECK(t.edges == 3);
  CHECK(t.faces == 1);
  CHECK(t.euler == 1);
  check_betti(t, 1, 0, 0);
}

TEST_CASE("topology: a cycle of three edges has b1 = 1", "[topology]") {
  const auto t = complex_topology(3, {{0, 1}, {1, 2}, {2, 0}}, {});
  CHECK(t.euler == 0);
  check_betti(t, 1, 1, 0);
}

TEST_CASE("topology: a hollow tetrahedron has b2 = 1", "[topology]") {
  const auto t = complex_topology(4, {}, {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}});
  CHECK(t.euler == 2);
  check_betti(t, 1, 0, 1);
}

TEST_CASE("topology: two hollow tetrahedra sharing a triangle have b2 = 2", "[topology]") {
  // No free face anywhere: the column reduction does all the work.
  const auto t = complex_topology(5, {}, {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}, {0, 4, 1}, {1, 4, 2}, {0, 2, 4}});
  CHECK(t.faces == 7);
  CHECK(t.edges == 9);
  check_betti(t, 1, 0, 2);
}

TEST_CASE("topology: ring complexes have b1 = 1", "[topology]") {
  SECTION("a triangulated annulus") {
    const auto t = complex_topology(24, {}, annulus(12));
    CHECK(t.euler == 0);
    check_betti(t, 1, 1, 0);
  }
  SECTION("a cycle of edges") {
    std::vector<Segment> edges;
    for (Index i = 0; i < 10; ++i) edges.push_back({i, (i + 1) % 10});
    check_betti(complex_topology(10, edges, {}), 1, 1, 0);
  }
  SECTION("a cycle of triangles sharing vertices only, plus a hanging edge") {
    // Triangles (0,1,2), (2,3,4), (4,5,0): a necklace, whose hole is the cycle 0-2-4.
    const auto t = complex_topology(7, {{5, 6}}, {{0, 1, 2}, {2, 3, 4}, {4, 5, 0}});
    check_betti(t, 1, 1, 0);
  }
}

TEST_CASE("topology: components, isolated vertices, duplicates and degenerate elements", "[topology]") {
  // Two disjoint triangles, one listed twice in another order, a degenerate triangle that is
  // really the edge 3-6, and an isolated vertex 7.
  const auto t = complex_topology(8, {{0, 1}, {1, 1}}, {{0, 1, 2}, {3, 4, 5}, {2, 1, 0}, {3, 3, 6}});
  CHECK(t.faces == 2);
  CHECK(t.edges == 7);
  check_betti(t, 3, 0, 0);
  CHECK_THROWS_AS(complex_topology(2, {{0, 2}}, {}), std::invalid_argument);
}

TEST_CASE("topology: a book of three pages is contractible", "[topology]") {
  const auto t = complex_topology(5, {}, {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}});
  check_betti(t, 1, 0, 0);
}

TEST_CASE("topology: surface topology of closed and open meshes", "[topology]") {
  SECTION("sphere") {
    const auto s = services::surface_topology(testing::make_sphere(1.0, 4));
    CHECK(s.closed());
    check_betti(s.complex, 1, 0, 1);
    CHECK(s.genus() == 0);
  }
  SECTION("torus") {
    const auto s = services::surface_topology(testing::make_torus(1.0, 0.3, 48, 24));
    CHECK(s.closed());
    CHECK(s.complex.euler == 0);
    check_betti(s.complex, 1, 2, 1);
    CHECK(s.genus() == 1);
  }
  SECTION("two spheres and an unused vertex") {
    SurfaceMesh a = testing::make_sphere(1.0, 2), b = testing::make_sphere(1.0, 1);
    const Index offset = static_cast<Index>(a.vertices.size());
    a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (Tri f : b.faces) a.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
    a.vertices.push_back(Vec3(9, 9, 9));
    const auto s = services::surface_topology(a);
    CHECK(s.complex.euler == 4);
    check_betti(s.complex, 2, 0, 2);
    CHECK(s.genus() == 0);
  }
  SECTION("a sphere with a hole") {
    SurfaceMesh m = testing::make_sphere(1.0, 3);
    m.faces.pop_back();
    const auto s = services::surface_topology(m);
    CHECK_FALSE(s.closed());
    CHECK(s.boundary_edges == 3);
    check_betti(s.complex, 1, 0, 0);
    CHECK(s.genus() == -1);
  }
}
