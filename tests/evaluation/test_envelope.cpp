// The sphere/cone/slab envelope service: closed-form distances against brute-force
// minimisation, the hierarchy against a linear scan (and its paired child bounds against the
// nodes' own), boundary points against shapes whose envelope is known exactly, and the same
// results on one and two threads.
#include <medax/services/envelope.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/testing/shapes.hpp>

#include "envelope_bvh.hpp"  // the service's internal hierarchy (framework/services)

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <tbb/task_arena.h>

#include <cmath>
#include <random>

using namespace medax;
using services::Envelope;

namespace {

constexpr double kPi = 3.14159265358979323846;

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}
Vec3 random_point(std::mt19937_64& rng, double lo, double hi) {
  return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}

/// min over a barycentric grid of |x − c(λ)| − r(λ): an upper bound on the exact minimum, close
/// to it for a fine grid.
double brute_force_slab(const Vec3& x, const std::array<Vec3, 3>& c, const std::array<double, 3>& r, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double a = double(i) / n, b = double(j) / n, w = 1 - a - b;
      const Vec3 centre = w * c[0] + a * c[1] + b * c[2];
      best = std::min(best, (x - centre).norm() - (w * r[0] + a * r[1] + b * r[2]));
    }
  return best;
}

double brute_force_cone(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n;
    best = std::min(best, (x - ((1 - t) * c0 + t * c1)).norm() - ((1 - t) * r0 + t * r1));
  }
  return best;
}

MedialComplex capsule_complex(double radius, double half_length) {
  MedialComplex mc;
  mc.add_vertex({0, 0, -half_length}, radius);
  mc.add_vertex({0, 0, half_length}, radius);
  mc.add_edge(0, 1);
  return mc;
}

/// A random complex of `nv` vertices with random triangles, edges and isolated vertices.
MedialComplex random_complex(std::mt19937_64& rng, Index nv, int nf, int ne) {
  MedialComplex mc;
  for (Index v = 0; v < nv; ++v) mc.add_vertex(random_point(rng, -1, 1), uniform(rng, 0.02, 0.4));
  const auto pick = [&] { return static_cast<Index>(rng() % (nv - 3)); };  // the last 3 stay isolated
  for (int f = 0; f < nf; ++f) {
    const Index a = pick(), b = pick(), c = pick();
    if (a != b && b != c && a != c) mc.add_face(a, b, c);
  }
  for (int e = 0; e < ne; ++e) {
    const Index a = pick(), b = pick();
    if (a != b) mc.add_edge(a, b);
  }
  return mc;
}

}  // namespace

TEST_CASE("envelope: cone and slab closed forms agree with brute-force minimisation", "[envelope]") {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const std::array<Vec3, 3> c{random_point(rng, -1, 1), random_point(rng, -1, 1), random_point(rng, -1, 1)};
    const std::array<double, 3> r{uniform(rng, 0.0, 0.8), uniform(rng, 0.0, 0.8), uniform(rng, 0.0, 0.8)};
    const Vec3 x = random_point(rng, -2, 2);
    // Grid error bound: the objective is (1 + |∇r|)-Lipschitz along the element; a grid of n
    // cells is within (longest side)/n of any point.
    const double side = std::max({(c[0] - c[1]).norm(), (c[1] - c[2]).norm(), (c[0] - c[2]).norm()});
    const int n = 400;
    const double grid_error = 2.0 * (side + 2.0) / n;

    const double cone = services::cone_signed_distance(x, c[0], r[0], c[1], r[1]);
    const double cone_bf = brute_force_cone(x, c[0], r[0], c[1], r[1], 20000);
    CHECK(cone <= cone_bf + 1e-12);
    CHECK(cone_bf - cone <= 1e-6);

    const double slab = services::slab_signed_distance(x, c[0], r[0], c[1], r[1], c[2], r[2]);
    const double slab_bf = brute_force_slab(x, c, r, n);
    CHECK(slab <= slab_bf + 1e-12);
    CHECK(slab_bf - slab <= grid_error);
    // A slab contains the cones of its sides.
    CHECK(slab <= cone + 1e-12);
  }
}

TEST_CASE("envelope: closed forms on cases with a known answer", "[envelope]") {
  // Cylinder part of a capsule: distance to the axis minus the radius.
  CHECK(services::cone_signed_distance({0.5, 0, 0.2}, {0, 0, -1}, 0.3, {0, 0, 1}, 0.3) == Approx(0.2).margin(1e-14));
  CHECK(services::cone_signed_distance({0, 0, 0.2}, {0, 0, -1}, 0.3, {0, 0, 1}, 0.3) == Approx(-0.3).margin(1e-14));
  // Beyond an end: the end sphere.
  CHECK(services::cone_signed_distance({0, 0, 2}, {0, 0, -1}, 0.3, {0, 0, 1}, 0.3) == Approx(0.7).margin(1e-14));
  // One sphere inside the other: the big one.
  CHECK(services::cone_signed_distance({0, 3, 0}, {0, 0, 0}, 2.0, {0.5, 0, 0}, 0.1) == Approx(1.0).margin(1e-14));
  // Slab of equal radii: a thick triangle; above its interior the height minus the radius.
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  CHECK(services::slab_signed_distance({0.5, 0.5, 1.0}, a, 0.25, b, 0.25, c, 0.25) == Approx(0.75).margin(1e-14));
  CHECK(services::slab_signed_distance({0.5, 0.5, -0.1}, a, 0.25, b, 0.25, c, 0.25) == Approx(-0.15).margin(1e-14));
  // Tapered slab, radii 0.1 + 0.1·x: the tangent planes have slope; the exact value for a
  // point above the interior is |h|·√(1−|g|²) − r(foot), here g = (0.1, 0, 0).
  const double expected = 1.0 * std::sqrt(1 - 0.01) - (0.1 + 0.1 * 0.5);
  CHECK(services::slab_signed_distance({0.5, 0.5, 1.0}, a, 0.1, b, 0.3, c, 0.1) == Approx(expected).margin(1e-14));
}

TEST_CASE("envelope: distance equals brute force over every element of a random complex", "[envelope]") {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    const MedialComplex mc = random_complex(rng, 40, 30, 25);
    const Envelope envelope(mc);
    for (int i = 0; i < 2000; ++i) {
      const Vec3 x = random_point(rng, -1.6, 1.6);
      // Independent brute force: every vertex sphere, every edge cone (listed edges and triangle
      // sides), every slab; the envelope keeps only maximal elements.
      double bf = std::numeric_limits<double>::infinity();
      for (std::size_t v = 0; v < mc.num_vertices(); ++v)
        bf = std::min(bf, services::sphere_signed_distance(x, mc.centres[v], mc.radii[v]));
      for (const Segment& e : mc.edges)
        bf = std::min(bf, services::cone_signed_distance(x, mc.centres[e[0]], mc.radii[e[0]], mc.centres[e[1]],
                                                         mc.radii[e[1]]));
      for (const Tri& f : mc.faces)
        for (int k = 0; k < 3; ++k)
          bf = std::min(bf, services::cone_signed_distance(x, mc.centres[f[k]], mc.radii[f[k]],
                                                           mc.centres[f[(k + 1) % 3]], mc.radii[f[(k + 1) % 3]]));
      for (const Tri& f : mc.faces)
        bf = std::min(bf, services::slab_signed_distance(x, mc.centres[f[0]], mc.radii[f[0]], mc.centres[f[1]],
                                                         mc.radii[f[1]], mc.centres[f[2]], mc.radii[f[2]]));
      const double d = envelope.signed_distance(x);
      REQUIRE(d == Approx(bf).margin(1e-12));
      REQUIRE(d == envelope.signed_distance_brute_force(x));
      const services::EnvelopeHit hit = envelope.closest(x);
      REQUIRE(hit.distance == d);
      // The reported ball realises the value.
      REQUIRE((x - hit.centre).norm() - hit.radius == Approx(d).margin(1e-9));
    }
  }
}

TEST_CASE("envelope: only maximal elements become primitives", "[envelope]") {
  MedialComplex mc;
  for (int v = 0; v < 6; ++v) mc.add_vertex(Vec3(v, 0, 0), 0.1);
  mc.add_face(0, 1, 2);
  mc.add_face(2, 1, 0);  // duplicate
  mc.add_edge(0, 1);     // a side
  mc.add_edge(3, 4);     // a cone
  mc.add_face(4, 4, 3);  // degenerate: the same edge again
  const Envelope envelope(mc);
  REQUIRE(envelope.primitives().size() == 3);  // sphere 5, cone 3-4, slab 0-1-2
  CHECK(envelope.primitives()[0].count == 1);
  CHECK(envelope.primitives()[0].vertices[0] == 5);
  CHECK(envelope.primitives()[1].count == 2);
  CHECK(envelope.primitives()[2].count == 3);
}

TEST_CASE("envelope: boundary points of a sphere envelope lie on the sphere", "[envelope][sampling]") {
  MedialComplex mc;
  const double radius = 0.7;
  mc.add_vertex({0.1, -0.2, 0.3}, radius);
  const Envelope envelope(mc);
  const double step = 2 * radius / 150;
  const services::EnvelopeSamples s = envelope.sample_boundary(step);
  REQUIRE(s.size() > 1000);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3 d = s.points[i] - mc.centres[0];
    REQUIRE(d.norm() == Approx(radius).margin(1e-9));
    REQUIRE(s.normals[i].dot(d.normalized()) == Approx(1.0).margin(1e-9));
  }
  // Area-weighted estimate of the area (step² / ‖n‖₁ per grid-edge crossing).
  CHECK(s.total_area() == Approx(4 * kPi * radius * radius).epsilon(0.005));
}

TEST_CASE("envelope: boundary points of a capsule envelope: position, area and coverage", "[envelope][sampling]") {
  const double radius = 0.3, half = 0.7;
  const Envelope envelope(capsule_complex(radius, half));
  const double step = 2 * radius / 150;
  const services::EnvelopeSamples s = envelope.sample_boundary(step);
  for (const Vec3& p : s.points) REQUIRE(testing::capsule_axis_distance(p, half) == Approx(radius).margin(1e-9));
  const double area = 4 * kPi * radius * radius + 2 * kPi * radius * 2 * half;
  CHECK(s.total_area() == Approx(area).epsilon(0.005));
  // Covering radius: every point of the exact boundary is within `step` of a sample.
  std::mt19937_64 rng(3);
  const services::PointIndex index(s.points);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 dir = random_point(rng, -1, 1).normalized();
    // A point of the exact capsule boundary: cylinder or a hemisphere, by area.
    Vec3 p;
    if (uniform(rng, 0, area) < 2 * kPi * radius * 2 * half) {
      const Vec3 radial = Vec3(dir.x(), dir.y(), 0).normalized();
      p = radius * radial + Vec3(0, 0, uniform(rng, -half, half));
    } else {
      p = radius * dir + Vec3(0, 0, dir.z() >= 0 ? half : -half);
    }
    worst = std::max(worst, index.nearest(p).second);
  }
  INFO("covering radius / step = " << worst / step);
  CHECK(worst < step);
}

TEST_CASE("envelope: distance to the boundary inside a union is deeper than inside any one primitive", "[envelope]") {
  // Two unit balls centred at (±0.5, 0, 0): from the origin the union's boundary is the
  // intersection circle, at √0.75, while each ball alone is only 0.5 deep there.
  MedialComplex mc;
  mc.add_vertex({-0.5, 0, 0}, 1.0);
  mc.add_vertex({0.5, 0, 0}, 1.0);
  const Envelope envelope(mc);
  const double step = 2.0 / 150;
  const services::EnvelopeSamples s = envelope.sample_boundary(step);
  const std::vector<Vec3> points{{0, 0, 0}, {3, 0, 0}, {0, 0.2, 0}};
  const std::vector<double> d = envelope.boundary_distances(points, s);
  CHECK(envelope.signed_distance(points[0]) == Approx(-0.5));
  CHECK(d[0] == Approx(std::sqrt(0.75)).margin(step));
  CHECK(d[0] >= std::sqrt(0.75) - 1e-9);  // the samples lie on the boundary: an upper bound
  CHECK(d[1] == Approx(1.5).margin(1e-12));  // outside: exact
  CHECK(d[2] == Approx(std::sqrt(0.75) - 0.2).margin(step));
}

TEST_CASE("envelope: a finer local grid tightens an inside distance the samples only bound", "[envelope]") {
  // The two unit balls above; from (0, 0, 0.7) each ball is 1 − √0.74 ≈ 0.140 deep, but the
  // closest point of either sphere is inside the other: the union's boundary is the intersection
  // circle, at √0.75 − 0.7 ≈ 0.166.
  MedialComplex mc;
  mc.add_vertex({-0.5, 0, 0}, 1.0);
  mc.add_vertex({0.5, 0, 0}, 1.0);
  const Envelope envelope(mc);
  const double coarse = 0.2, fine = 0.05;
  const services::EnvelopeSamples s = envelope.sample_boundary(coarse);
  const std::vector<Vec3> points{{0, 0, 0.7}, {3, 0, 0}, {-1.2, 0, 0}};
  const std::vector<double> bound = envelope.boundary_distances(points, s);
  const std::vector<double> refined = envelope.boundary_distances(points, s, nullptr, {}, fine);
  const double exact = std::sqrt(0.75) - 0.7;
  CHECK(bound[0] >= exact - 1e-9);
  CHECK(refined[0] >= exact - 1e-9);  // still an upper bound: the points are on ∂E
  INFO("exact " << exact << ", samples' bound " << bound[0] << ", refined " << refined[0]);
  CHECK(refined[0] < bound[0]);       // the finer grid's points are nearer the circle,
  CHECK(refined[0] <= exact + fine);  // within its covering radius
  CHECK(refined[1] == bound[1]);  // outside: exact either way
  CHECK(refined[2] == bound[2]);  // certified (0.3 inside the first ball's cap): exact either way
  CHECK(refined[2] == Approx(0.3).margin(1e-12));
  // A step not below the samples' asks for nothing.
  CHECK(envelope.boundary_distances(points, s, nullptr, {}, coarse) == bound);
}

TEST_CASE("envelope: an empty complex has an empty envelope", "[envelope]") {
  const Envelope envelope{MedialComplex{}};
  CHECK(envelope.empty());
  CHECK(envelope.sample_boundary(0.1).size() == 0);
  CHECK(std::isinf(envelope.signed_distance({0, 0, 0})));
}

TEST_CASE("envelope: invalid input is refused", "[envelope]") {
  MedialComplex mc;
  mc.add_vertex({0, 0, 0}, 1);
  mc.add_edge(0, 3);
  CHECK_THROWS_AS(Envelope(mc), std::invalid_argument);
  MedialComplex ok;
  ok.add_vertex({0, 0, 0}, 1);
  CHECK_THROWS_AS(Envelope(ok).sample_boundary(0.0), std::invalid_argument);
}

namespace {

/// Exact mean over the capsule boundary (radius ρ, half length L) of |R − |q||: the distance
/// from its points to the sphere of radius R about the centre, by Simpson's rule on the
/// cylinder (area 2πρ dz) and the caps (area 2πρ² dt, t = cosine to the axis).
double capsule_to_sphere_mean(double rho, double half, double big_r) {
  const int n = 200000;
  const auto simpson = [n](auto f, double a, double b) {
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
    return sum * h / 3;
  };
  const double cylinder =
      simpson([&](double z) { return std::abs(big_r - std::sqrt(rho * rho + z * z)) * 2 * kPi * rho; }, -half, half);
  const double caps = 2 * simpson(
                              [&](double t) {
                                return std::abs(big_r - std::sqrt(half * half + rho * rho + 2 * half * rho * t)) *
                                       2 * kPi * rho * rho;
                              },
                              0.0, 1.0);
  return (cylinder + caps) / (4 * kPi * rho * half + 4 * kPi * rho * rho);
}

}  // namespace

TEST_CASE("envelope: error of the envelope-to-surface measurement on a known answer", "[envelope][sampling]") {
  // Envelope: the capsule ρ = 0.3, L = 0.7 (two spheres and a cone). "Surface": the exact sphere
  // R = 1 about its centre, so that the distance from a boundary point q is |1 − |q|| with no
  // tessellation error. Exact values: max 0.7 (the cylinder's middle ring, |q| = ρ), mean from
  // capsule_to_sphere_mean. Step as the VMAS code: smallest side of the shape's box (2) / 150.
  const double rho = 0.3, half = 0.7;
  const Envelope envelope(capsule_complex(rho, half));
  const double step = 2.0 / 150;
  const services::EnvelopeSamples s = envelope.sample_boundary(step);
  double mx = 0, weighted = 0, area = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double d = std::abs(1.0 - s.points[i].norm());
    mx = std::max(mx, d);
    weighted += s.areas[i] * d;
    area += s.areas[i];
  }
  const double exact_mean = capsule_to_sphere_mean(rho, half, 1.0);
  INFO("max " << mx << " (exact 0.7), mean " << weighted / area << " (exact " << exact_mean << "), step " << step);
  // The maximum is attained on a whole ring: sampled to well within a step.
  CHECK(mx <= 0.7 + 1e-9);
  CHECK(mx >= 0.7 - 0.1 * step);
  CHECK(weighted / area == Approx(exact_mean).epsilon(0.002));
}

TEST_CASE("envelope: a hierarchy node's paired child bounds are the children's own, bit for bit", "[envelope]") {
  // The search reads both children's lower bounds from their parent's pair (two-lane arithmetic);
  // they must be the very doubles BvhNode::lower_bound gives, or the search order could change.
  using services::envelope_detail::BvhNode;
  using services::envelope_detail::ChildPair;
  std::mt19937_64 rng(17);
  const auto random_node = [&](std::uint32_t count) {
    BvhNode node;
    for (int k = 0; k < 3; ++k) {
      const double a = uniform(rng, -1, 1), b = uniform(rng, -1, 1);
      node.lo[k] = static_cast<float>(std::min(a, b));
      node.hi[k] = static_cast<float>(std::max(a, b));
      node.g[k] = static_cast<float>(uniform(rng, -0.5, 0.5));
    }
    node.rmax = static_cast<float>(uniform(rng, 0, 0.5));
    node.slope = static_cast<float>(uniform(rng, 0, 0.95));
    node.gamma = static_cast<float>(uniform(rng, -1, 1));
    node.first = static_cast<std::uint32_t>(rng() % 1000);
    node.count = count;
    return node;
  };
  for (int trial = 0; trial < 2000; ++trial) {
    const BvhNode left = random_node(trial % 3 == 0 ? 2 : 0), right = random_node(trial % 2 == 0 ? 1 : 0);
    ChildPair pair;
    pair.set(0, left, 7);
    pair.set(1, right, 9);
    // A leaf child leads to its primitives, an inner one to its own pair.
    CHECK(pair.index[0] == (left.count > 0 ? left.first : 7));
    CHECK(pair.index[1] == (right.count > 0 ? right.first : 9));
    CHECK(pair.count[0] == left.count);
    CHECK(pair.count[1] == right.count);
    for (int i = 0; i < 10; ++i) {
      // Points inside the boxes too (there the bounds are −r_max or the affine bound at the point).
      const Vec3 x = random_point(rng, -1.5, 1.5);
      double lb[2];
      pair.lower_bounds(x, lb);
      REQUIRE(lb[0] == left.lower_bound(x));
      REQUIRE(lb[1] == right.lower_bound(x));
    }
  }
}

TEST_CASE("envelope: boundary points and distances are the same on one and two threads", "[envelope][sampling]") {
  // The sampling runs its searches, the corner lookups, the crossing edges and the refinement in
  // parallel; results must not depend on the threads.
  std::mt19937_64 rng(23);
  const MedialComplex mc = random_complex(rng, 300, 300, 60);
  const Envelope envelope(mc);
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i) points.push_back(random_point(rng, -1.2, 1.2));
  const auto run = [&](int threads) {
    std::pair<services::EnvelopeSamples, std::vector<double>> out;
    tbb::task_arena(threads).execute([&] {
      out.first = envelope.sample_boundary(0.03);
      out.second = envelope.boundary_distances(points, out.first, nullptr, {}, 0.015);
    });
    return out;
  };
  const auto one = run(1), two = run(2);
  REQUIRE(one.first.size() > 1000);
  CHECK(one.first.points == two.first.points);
  CHECK(one.first.normals == two.first.normals);
  CHECK(one.first.areas == two.first.areas);
  CHECK(one.first.primitives == two.first.primitives);
  CHECK(one.second == two.second);
}
