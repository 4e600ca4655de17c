// Convergence on shapes with known medial axes (notes §4.2–4.3): ellipsoid and torus sampled at
// N = 2k, 8k, 32k. The output vertices approach the analytic inner medial axis (soundness, Thm 1)
// and cover it (Thm 2) better as N grows; and far fewer facets stray from the axis than in the
// raw interior Voronoi diagram of the same samples.
#include "fixtures.hpp"
#include "interior_voronoi.hpp"

#include <medax/services/kdtree.hpp>

#include <catch2/catch.hpp>

#include <functional>

using namespace medax;
using dz_test::quantile;

namespace {

constexpr double kA = 1.0, kB = 0.7, kC = 0.4;  // ellipsoid semi-axes
constexpr double kR = 1.0, kr = 0.35;           // torus radii

struct Level {
  std::size_t n = 0, vertices = 0, faces = 0;
  double median = 0, p95 = 0, coverage = 0, lemma7 = 0;
};

/// Distances from the output vertices to the axis, and from axis samples to the output.
Level measure(const MedialComplex& m, const std::function<double(const Vec3&)>& axis_distance,
              const std::vector<Vec3>& axis_samples) {
  Level l;
  l.vertices = m.num_vertices();
  l.faces = m.faces.size();
  std::vector<double> d;
  d.reserve(m.num_vertices());
  for (const Vec3& c : m.centres) d.push_back(axis_distance(c));
  l.median = quantile(d, 0.5);
  l.p95 = quantile(d, 0.95);
  const services::PointIndex index(m.centres);
  for (const Vec3& a : axis_samples) l.coverage = std::max(l.coverage, index.nearest(a).second);
  return l;
}

/// Triangles whose centroid is farther than `tolerance` from the axis.
std::size_t far_faces(const MedialComplex& m, const std::function<double(const Vec3&)>& axis_distance,
                      double tolerance) {
  std::size_t far = 0;
  for (const Tri& t : m.faces)
    far += axis_distance((m.centres[t[0]] + m.centres[t[1]] + m.centres[t[2]]) / 3) > tolerance;
  return far;
}

void check_decreasing(const std::vector<Level>& levels, bool check_coverage) {
  for (std::size_t i = 1; i < levels.size(); ++i) {
    CHECK(levels[i].median < levels[i - 1].median);
    CHECK(levels[i].p95 < levels[i - 1].p95);
    if (check_coverage) CHECK(levels[i].coverage < levels[i - 1].coverage);
  }
}

std::string describe(const std::vector<Level>& levels) {
  std::string s;
  for (const Level& l : levels)
    s += "N=" + std::to_string(l.n) + ": V " + std::to_string(l.vertices) + " F " + std::to_string(l.faces) +
         " median " + std::to_string(l.median) + " p95 " + std::to_string(l.p95) + " coverage " +
         std::to_string(l.coverage) + " lemma7 p95 " + std::to_string(l.lemma7) + "\n";
  return s;
}

}  // namespace

TEST_CASE("dey_zhao converges on the ellipsoid: distances to the analytic axis decrease with N",
          "[dey_zhao][convergence]") {
  const auto axis = [](const Vec3& p) { return testing::ellipsoid_axis_distance(p, kA, kB, kC); };
  // Coverage (Thm 2) over the axis region scaled by 0.9, where the medial angle is bounded below.
  const double A = (kA * kA - kC * kC) / kA, B = (kB * kB - kC * kC) / kB;
  std::vector<Vec3> region;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j) {
      const double x = 0.9 * A * i / 20.0, y = 0.9 * B * j / 20.0;
      if (x * x / (A * A) + y * y / (B * B) <= 0.81) region.emplace_back(x, y, 0);
    }
  std::vector<Level> levels;
  for (std::size_t n : {2000, 8000, 32000}) {
    const dz_test::Sampled s = dz_test::ellipsoid(kA, kB, kC, n);
    const MedialComplex m = dz_test::run(s);
    Level l = measure(m, axis, region);
    l.n = n;
    // Lemma 7: a point w of an Angle-selected facet (at p) with |w − p| <= mu lies within
    // O(eps) mu of m(p), the centre of the medial ball at p.
    const auto& P = m.get(dey_zhao::kDualP);
    const auto& Q = m.get(dey_zhao::kDualQ);
    const auto& bits = m.get(dey_zhao::kConditions);
    std::vector<double> rel;
    for (std::size_t f = 0; f < m.faces.size(); ++f)
      for (int end = 0; end < 2; ++end) {
        if (!(bits[f] & (end ? dey_zhao::kAngleQ : dey_zhao::kAngleP))) continue;
        const Vec3& p = s.points[end ? Q[f] : P[f]];
        const Vec3 centre(p.x() * (1 - kC * kC / (kA * kA)), p.y() * (1 - kC * kC / (kB * kB)), 0);
        const double mu = (p - centre).norm();
        for (Index v : m.faces[f])
          if ((m.centres[v] - p).norm() <= mu) rel.push_back((m.centres[v] - centre).norm() / mu);
      }
    l.lemma7 = quantile(rel, 0.95);
    levels.push_back(l);
  }
  INFO(describe(levels));
  check_decreasing(levels, true);
  for (std::size_t i = 1; i < levels.size(); ++i) CHECK(levels[i].lemma7 < levels[i - 1].lemma7);
  CHECK(levels.back().p95 < 2e-4);  // of a bounding-box diagonal of 2.4
}

TEST_CASE("dey_zhao converges on the torus: distances to the core circle decrease with N",
          "[dey_zhao][convergence]") {
  const auto axis = [](const Vec3& p) { return testing::torus_axis_distance(p, kR); };
  std::vector<Vec3> circle;
  for (int i = 0; i < 360; ++i) circle.emplace_back(kR * std::cos(i * dey_zhao::kPi / 180), kR * std::sin(i * dey_zhao::kPi / 180), 0);
  std::vector<Level> levels;
  for (std::size_t n : {2000, 8000, 32000}) {
    const dz_test::Sampled s = dz_test::torus(kR, kr, n);
    Level l = measure(dz_test::run(s), axis, circle);
    l.n = n;
    levels.push_back(l);
  }
  INFO(describe(levels));
  check_decreasing(levels, true);
  CHECK(levels.back().median < 1e-4);
}

TEST_CASE("dey_zhao: fewer facets far from the true axis than the raw interior Voronoi diagram",
          "[dey_zhao][convergence]") {
  for (std::size_t n : {2000, 8000}) {
    for (int shape = 0; shape < 2; ++shape) {
      const dz_test::Sampled s = shape ? dz_test::torus(kR, kr, n) : dz_test::ellipsoid(kA, kB, kC, n);
      const std::function<double(const Vec3&)> axis =
          shape ? std::function<double(const Vec3&)>([](const Vec3& p) { return testing::torus_axis_distance(p, kR); })
                : [](const Vec3& p) { return testing::ellipsoid_axis_distance(p, kA, kB, kC); };
      const MedialComplex dz = dz_test::run(s);
      const MedialComplex raw = voronoi::interior_voronoi(s.points, s.mesh);
      // "far": more than 2.5% of the smallest feature (the semi-axis c, the tube radius r)
      const double tolerance = 0.025 * (shape ? kr : kC);
      const std::size_t dz_far = far_faces(dz, axis, tolerance), raw_far = far_faces(raw, axis, tolerance);
      INFO((shape ? "torus" : "ellipsoid") << " N=" << n << ": far triangles dey_zhao " << dz_far << " of "
                                           << dz.faces.size() << ", voronoi " << raw_far << " of " << raw.faces.size());
      CHECK(raw_far > 100);
      CHECK(dz_far * 20 < raw_far);
    }
  }
}
