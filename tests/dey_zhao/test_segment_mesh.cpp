// The segment test of the `mesh` inner selection (SegmentMeshTest: box hierarchy, exact
// orientations) against its definition, CGAL::do_intersect of the segment with every triangle,
// on segments built to touch: between mesh vertices (along faces, through edges), from a
// vertex into the solid, grazing a face, axis-parallel, at scales far from 1.
#include "segment_mesh.hpp"

#include <medax/testing/shapes.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace medax;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

/// The definition: the segment meets a non-degenerate triangle.
bool meets_by_definition(const SurfaceMesh& mesh, const Vec3& a, const Vec3& b) {
  for (const Tri& f : mesh.faces) {
    const K::Point_3 p = point(mesh.vertices[f[0]]), q = point(mesh.vertices[f[1]]), r = point(mesh.vertices[f[2]]);
    if (!CGAL::collinear(p, q, r) && CGAL::do_intersect(K::Triangle_3(p, q, r), K::Segment_3(point(a), point(b))))
      return true;
  }
  return false;
}

/// Segments that touch the mesh in every way: vertex to vertex, vertex to a point between two
/// vertices, a vertex pair shrunk by 1/16 (as the inner test does), random points in the box,
/// segments parallel to an axis through a vertex, and segments from outside that end on a vertex
/// (met at the far end only: the slab test's rounding there is what its margin covers).
std::vector<std::array<Vec3, 2>> touching_segments(const SurfaceMesh& mesh, std::size_t count) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::size_t> vertex(0, mesh.vertices.size() - 1);
  std::uniform_real_distribution<double> unit(-1.3, 1.3);
  std::vector<std::array<Vec3, 2>> out;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 &a = mesh.vertices[vertex(rng)], &b = mesh.vertices[vertex(rng)], &c = mesh.vertices[vertex(rng)];
    const Vec3 d = b - a;
    switch (i % 6) {
      case 0: out.push_back({a, b}); break;
      case 1: out.push_back({a, 0.5 * (b + c)}); break;
      case 2: out.push_back({a + d / 16, b - d / 16}); break;
      case 3: out.push_back({Vec3(unit(rng), unit(rng), unit(rng)), Vec3(unit(rng), unit(rng), unit(rng))}); break;
      case 4: out.push_back({1.5 * a + 0.1 * Vec3(unit(rng), unit(rng), unit(rng)), a}); break;
      default: {
        Vec3 e = a;
        e[static_cast<int>(i / 6 % 3)] += unit(rng);
        out.push_back({a, e});
      }
    }
  }
  return out;
}

/// Compares the test with the definition on every segment; returns how many meet the mesh.
std::size_t check_against_definition(const SurfaceMesh& mesh, const std::vector<std::array<Vec3, 2>>& segments) {
  const dey_zhao::SegmentMeshTest test(mesh);
  std::size_t meeting = 0;
  for (const auto& [a, b] : segments) {
    const bool expected = meets_by_definition(mesh, a, b);
    INFO("segment (" << a.transpose() << ") - (" << b.transpose() << ")");
    REQUIRE(test.meets(a, b) == expected);
    REQUIRE(test.meets(b, a) == expected);
    meeting += expected;
  }
  return meeting;
}

}  // namespace

TEST_CASE("dey_zhao segment test: agrees with do_intersect on every triangle, touching cases included",
          "[dey_zhao][inner]") {
  // A box with coplanar faces (segments along them, through grid edges and vertices) and a
  // curved mesh, each scaled by 2^-30, 1 and 2^40 (exact; the culling margin is relative).
  for (const SurfaceMesh& shape : {testing::make_box(1.0, 0.75, 0.5, 3), testing::make_ellipsoid(1.0, 0.7, 0.4, 2)}) {
    const std::vector<std::array<Vec3, 2>> segments = touching_segments(shape, 3000);
    std::size_t meeting_at_scale_1 = 0;
    for (int power : {0, -30, 40}) {
      const double f = std::ldexp(1.0, power);
      SurfaceMesh mesh = shape;
      for (Vec3& v : mesh.vertices) v *= f;
      std::vector<std::array<Vec3, 2>> scaled = segments;
      for (auto& s : scaled) s[0] *= f, s[1] *= f;
      INFO("faces " << mesh.faces.size() << ", scale 2^" << power);
      const std::size_t meeting = check_against_definition(mesh, scaled);
      CHECK(meeting > segments.size() / 4);  // both answers are well represented
      CHECK(meeting < segments.size() * 9 / 10);
      if (power == 0) meeting_at_scale_1 = meeting;
      CHECK(meeting == meeting_at_scale_1);
    }
  }
}
