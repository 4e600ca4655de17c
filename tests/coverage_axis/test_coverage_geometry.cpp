// Coverage Axis on an analytic shape (the unit sphere): every coverable sample lies in a selected
// dilated ball, checked from the geometry; the optimum is monotone in δ and in the samples;
// geometric dominance keeps the optimum.
#include "coverage_matrix.hpp"
#include "presolve.hpp"
#include "set_cover_exact.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace medax;
using namespace medax::coverage_axis;

namespace {

std::vector<Vec3> sphere_samples(std::size_t count, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  std::vector<Vec3> points(count);
  for (Vec3& p : points) p = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
  return points;
}

/// Random inner balls of the unit sphere, each touching it (radius 1 − |c|).
Balls inner_balls(std::size_t count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Balls balls;
  while (balls.centres.size() < count) {
    const Vec3 c(unit(rng), unit(rng), unit(rng));
    if (c.norm() >= 0.95) continue;
    balls.centres.push_back(c);
    balls.radii.push_back(1 - c.norm());
  }
  return balls;
}

std::size_t minimum_cover(const std::vector<Vec3>& samples, const Balls& balls, double dilation) {
  const CoverageMatrix m = coverage_matrix(samples, balls, dilation);
  return solve_exact(m.cover, ExactOptions{}).chosen.size();
}

}  // namespace

TEST_CASE("coverage: every coverable sample is in a selected dilated ball, from the geometry",
          "[coverage_axis][geometry]") {
  std::mt19937_64 rng(5);
  const std::vector<Vec3> samples = sphere_samples(300, rng);
  const Balls balls = inner_balls(400, rng);
  const double dilation = 0.05;
  const CoverageMatrix m = coverage_matrix(samples, balls, dilation);
  CHECK(m.covered_samples.size() + m.uncoverable == samples.size());
  const ExactResult r = solve_exact(m.cover, ExactOptions{});
  std::size_t uncoverable = 0;
  for (const Vec3& s : samples) {
    bool coverable = false, covered = false;
    for (std::size_t i = 0; i < balls.centres.size(); ++i)
      coverable = coverable || (s - balls.centres[i]).norm() < balls.radii[i] + dilation;
    for (Index i : r.chosen) covered = covered || (s - balls.centres[i]).norm() < balls.radii[i] + dilation;
    uncoverable += coverable ? 0 : 1;
    if (coverable) CHECK(covered);
  }
  CHECK(uncoverable == m.uncoverable);
}

TEST_CASE("coverage: the optimum does not increase with δ nor decrease with more samples",
          "[coverage_axis][geometry]") {
  std::mt19937_64 rng(9);
  const std::vector<Vec3> samples = sphere_samples(240, rng);
  const Balls balls = inner_balls(300, rng);
  std::size_t previous = samples.size() + 1;
  for (double dilation : {0.02, 0.05, 0.1, 0.2}) {
    const std::size_t optimum = minimum_cover(samples, balls, dilation);
    INFO("dilation " << dilation);
    CHECK(optimum <= previous);
    previous = optimum;
  }
  previous = 0;
  for (std::size_t count : {60u, 120u, 240u}) {
    const std::vector<Vec3> first(samples.begin(), samples.begin() + count);
    const std::size_t optimum = minimum_cover(first, balls, 0.05);
    INFO("samples " << count);
    CHECK(optimum >= previous);
    previous = optimum;
  }
}

TEST_CASE("presolve: geometric dominance drops only balls inside another, and keeps the optimum",
          "[coverage_axis][presolve]") {
  std::mt19937_64 rng(13);
  const std::vector<Vec3> samples = sphere_samples(200, rng);
  Balls balls = inner_balls(250, rng);
  balls.centres.push_back(balls.centres[0]), balls.radii.push_back(balls.radii[0]);  // a duplicate
  balls.centres.push_back(balls.centres[1]), balls.radii.push_back(0.5 * balls.radii[1]);  // a nested ball
  const double dilation = 0.05;
  const std::vector<Index> kept = geometrically_undominated(balls, dilation);
  CHECK(kept.size() < balls.centres.size());
  CHECK(std::find(kept.begin(), kept.end(), Index(250)) == kept.end());
  CHECK(std::find(kept.begin(), kept.end(), Index(251)) == kept.end());
  for (Index a = 0; a < balls.centres.size(); ++a) {
    if (std::binary_search(kept.begin(), kept.end(), a)) continue;
    bool inside = false;  // a dropped ball lies in a kept one
    for (Index b : kept)
      inside = inside || (balls.centres[a] - balls.centres[b]).norm() + balls.radii[a] <= balls.radii[b] + 1e-12;
    CHECK(inside);
  }
  Balls reduced;
  for (Index i : kept) reduced.centres.push_back(balls.centres[i]), reduced.radii.push_back(balls.radii[i]);
  CHECK(minimum_cover(samples, reduced, dilation) == minimum_cover(samples, balls, dilation));
}
