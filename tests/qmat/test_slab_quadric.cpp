// The slab quadric error metric and the stability ratio (notes §1.2, §1.5, §1.8).
#include "collapse.hpp"
#include "qmat_test_inputs.hpp"

#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <stdexcept>

using namespace medax;
using namespace medax::qmat;

TEST_CASE("stability ratio: in [0, 1], 1 for equal radii, 0 iff one sphere contains the other", "[qmat][quadric]") {
  CHECK(stability_ratio(sphere4({0, 0, 0}, 1), sphere4({3, 0, 0}, 1)) == Approx(1));
  CHECK(stability_ratio(sphere4({0, 0, 0}, 2), sphere4({1, 0, 0}, 1)) == 0);    // internally tangent
  CHECK(stability_ratio(sphere4({0, 0, 0}, 2), sphere4({0.5, 0, 0}, 1)) == 0);  // contained
  CHECK(stability_ratio(sphere4({1, 1, 1}, 2), sphere4({1, 1, 1}, 1)) == 0);    // same centre
  CHECK(stability_ratio(sphere4({0, 0, 0}, 2), sphere4({2, 0, 0}, 1)) == Approx(0.5));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.01, 1);
  for (int k = 0; k < 1000; ++k) {
    const Vec4 a = sphere4({u(rng), u(rng), u(rng)}, u(rng)), b = sphere4({u(rng), u(rng), u(rng)}, u(rng));
    const double g = stability_ratio(a, b);
    CHECK(g >= 0);
    CHECK(g <= 1);
    const double d = (centre_of(a) - centre_of(b)).norm();
    CHECK((g == 0) == (d <= std::abs(a.w() - b.w())));
  }
}

TEST_CASE("slab normals: both planes touch all three spheres", "[qmat][quadric]") {
  const Vec4 m0 = sphere4({0, 0, 0}, 0.5), m1 = sphere4({2, 0, 0}, 0.3), m2 = sphere4({0, 1.5, 0.2}, 0.4);
  const auto normals = slab_normals(m0, m1, m2);
  REQUIRE(normals);
  for (const Vec3& n : *normals) {
    CHECK(n.norm() == Approx(1));
    // The plane n·x = n·c₀ + r₀ is tangent to every sphere: n·cᵢ + rᵢ is the same for all.
    CHECK(n.dot(centre_of(m1)) + m1.w() == Approx(n.dot(centre_of(m0)) + m0.w()));
    CHECK(n.dot(centre_of(m2)) + m2.w() == Approx(n.dot(centre_of(m0)) + m0.w()));
  }
  CHECK(!slab_normals(m0, sphere4({1e-9, 0, 0}, 0.5), m2));       // centres too close
  CHECK(!slab_normals(m0, sphere4({0.1, 0, 0}, 3), m2));          // one sphere swallows the slab
}

TEST_CASE("vertex quadrics: Q_v >= 0 and Q_v(m_v) = 0 at initialisation on real Voronoi axes",
          "[qmat][quadric]") {
  for (const char* file : {"ellipsoid.off", "joint.off"}) {
    const MedialComplex axis = test::voronoi_axis(file);
    const CollapseMesh mesh(axis, default_unit_length(axis));
    const InitialQuadrics q = initial_quadrics(mesh, {});
    std::mt19937_64 rng(3);
    std::normal_distribution<double> step(0, 0.01);
    std::size_t with_planes = 0;
    for (Index v = 0; v < mesh.size(); ++v) {
      const Vec4& m = mesh.spheres[v];
      const SlabQuadric slab = q.slab[v].plus(PackedQuadric{});
      CHECK(std::abs(slab(m)) <= 1e-12);
      const Vec4 s = m + Vec4(step(rng), step(rng), step(rng), step(rng));
      CHECK(slab(s) >= -1e-14);
      if (q.add_of[v] != InitialQuadrics::kNoAdd)  // add terms are anchored at m_v as well
        CHECK(q.add[q.add_of[v]](m) == Approx(0).margin(1e-12));
      if (slab.A.norm() > 0) {  // a vertex with slab planes: positive off its sphere
        ++with_planes;
        CHECK(slab(s) > 0);
      }
    }
    CHECK(with_planes + q.invalid_faces > 0);
    CHECK(with_planes > mesh.size() / 4);
  }
}

TEST_CASE("a flat equal-radius sheet gives a singular edge quadric", "[qmat][quadric]") {
  MedialComplex flat;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) flat.add_vertex(Vec3(i, j, 0), 0.5);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const Index a = 3 * i + j;
      flat.add_face(a, a + 3, a + 4);
      flat.add_face(a, a + 4, a + 1);
    }
  flat.close_edges();
  const CollapseMesh mesh(flat, 1.0);
  const InitialQuadrics q = initial_quadrics(mesh, {});
  CHECK(q.invalid_faces == 0);
  // Every plane is z = ±(… ) with n = ±e_z: A_e has rank ≤ 2, det 0.
  CHECK(std::abs(q.slab[4].plus(q.slab[5]).A.determinant()) <= 1e-12);
  CHECK(!q.slab[4].plus(q.slab[5]).minimiser(1e-12));
}

TEST_CASE("the 4x4 partial-pivot solve equals Eigen's PartialPivLU bit for bit", "[qmat][quadric]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  auto check = [](const Mat4& A, const Vec4& b) {
    const Vec4 eigen = A.partialPivLu().solve(b), ours = solve_partial_pivot(A, b);
    for (int k = 0; k < 4; ++k) CHECK(std::memcmp(&eigen[k], &ours[k], sizeof(double)) == 0);
  };
  for (int n = 0; n < 2000; ++n) {
    Mat4 A;
    for (int k = 0; k < 16; ++k) A(k / 4, k % 4) = u(rng);
    const Vec4 b(u(rng), u(rng), u(rng), u(rng));
    check(A, b);
    // The collapse's matrices: sums of tangent-plane quadrics, symmetric and often nearly singular.
    SlabQuadric q;
    for (int p = 0; p < 2 + n % 5; ++p)
      q += SlabQuadric::tangent_plane(Vec3(u(rng), u(rng), u(rng)).normalized(), Vec4(u(rng), u(rng), u(rng), 0.5));
    check(q.A, q.b);
    // Zero leading entries force row swaps.
    A.col(0).head<2>().setZero();
    check(A, b);
  }
}

TEST_CASE("packed vertex quadrics: unit-weight plane sums are symmetric bit for bit, and packed sums "
          "are the full sums' bits", "[qmat][quadric]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  auto plane_sum = [&](int planes) {
    SlabQuadric q;
    for (int p = 0; p < planes; ++p)
      q += SlabQuadric::tangent_plane(Vec3(u(rng), u(rng), u(rng)).normalized(), Vec4(u(rng), u(rng), u(rng), 0.7));
    return q;
  };
  auto same_bits = [](const SlabQuadric& x, const SlabQuadric& y) {
    return std::memcmp(x.A.data(), y.A.data(), sizeof(double) * 16) == 0 &&
           std::memcmp(x.b.data(), y.b.data(), sizeof(double) * 4) == 0 && std::memcmp(&x.c, &y.c, sizeof(double)) == 0;
  };
  for (int n = 0; n < 500; ++n) {
    const SlabQuadric x = plane_sum(1 + n % 7), y = plane_sum(1 + n % 3);
    PackedQuadric px = PackedQuadric::pack(x);
    const PackedQuadric py = PackedQuadric::pack(y);
    CHECK(same_bits(px.plus(py), x + y));
    CHECK(same_bits(px.plus(PackedQuadric{}), x));
    px += py;
    CHECK(same_bits(px.plus(PackedQuadric{}), x + y));
  }
  SlabQuadric skew;
  skew.A(0, 1) = 1;  // A(1, 0) stays 0
  CHECK_THROWS_AS(PackedQuadric::pack(skew), std::logic_error);
}
