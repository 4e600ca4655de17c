// Poisson-disk sampling service: exact count, minimum distances, coverage, areas, determinism
// (across seeds and thread counts); the dart-thrown candidates; the uniform samples' face search.
#include "conditioning_test_support.hpp"
// Private to the service: the areas with a chosen grid, to compare its two searches.
#include "../../framework/services/poisson_areas.hpp"
#include "../../framework/services/poisson_darts.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/services/poisson.hpp>
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

using namespace medax;
using namespace medax::services;

namespace {

void check_on_surface(const SurfaceMesh& mesh, const OrientedSamples& s) {
  REQUIRE(s.normals.size() == s.size());
  REQUIRE(s.areas.size() == s.size());
  const SurfaceDistance distance(mesh);
  const double tolerance = 1e-9 * bbox_diagonal(mesh.vertices);
  double worst = 0;
  for (double d : distance.distances(s.points)) worst = std::max(worst, d);
  CHECK(worst <= tolerance);
  for (std::size_t i = 0; i < s.size(); ++i) {
    CHECK(std::abs(s.normals[i].norm() - 1.0) < 1e-12);
    CHECK(s.areas[i] > 0);
  }
  CHECK(std::accumulate(s.areas.begin(), s.areas.end(), 0.0) == Approx(surface_area(mesh)).epsilon(1e-9));
}

}  // namespace

TEST_CASE("Poisson-disk by count: exact count, on the surface, blue-noise minimum distance", "[sampling]") {
  // A round, a CAD and a thin shape (turbine: a thin flanged housing).
  for (const auto& path : {test::data_dir() / "sphere.obj", test::corpus_mesh("fandisk.off"),
                           test::corpus_mesh("turbine.off")}) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    std::mt19937_64 rng(7);
    const std::size_t n = 3000;
    const OrientedSamples s = sample_poisson_count(mesh, n, rng);
    REQUIRE(s.size() == n);
    check_on_surface(mesh, s);
    // Sample elimination reaches about 0.69 of the hexagonal-packing spacing (measured on these
    // meshes: 0.68-0.70); uniform random samples come within a few percent of it.
    const double spacing = poisson_packing_distance(surface_area(mesh), n);
    const double poisson_min = min_sample_distance(s);
    CHECK(poisson_min >= 0.6 * spacing);
    std::mt19937_64 rng2(7);
    CHECK(min_sample_distance(sample_uniform(mesh, n, rng2)) < 0.2 * spacing);
  }
}

TEST_CASE("Poisson-disk by radius: no two samples closer than the radius", "[sampling]") {
  for (const auto& path : {test::data_dir() / "ellipsoid.off", test::corpus_mesh("fandisk.off"),
                           test::corpus_mesh("turbine.off")}) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    const double area = surface_area(mesh);
    const double r = poisson_packing_distance(area, 2000) * 0.7;
    std::mt19937_64 rng(3);
    const OrientedSamples s = sample_poisson_radius(mesh, r, rng);
    check_on_surface(mesh, s);
    CHECK(min_sample_distance(s) >= r);
    // Nearly maximal: about as many as elimination reaches at that spacing (2000 here).
    CHECK(s.size() > 1500);
    CHECK(s.size() < 2600);
  }
}

TEST_CASE("Poisson-disk samples the two sides of a thin plate independently", "[sampling]") {
  // A box 1 × 1 × 0.01: the faces 0.01 apart are far closer than the sample spacing.
  const SurfaceMesh plate = testing::make_box(0.5, 0.5, 0.005, 8);
  std::mt19937_64 rng(1);
  const OrientedSamples s = sample_poisson_count(plate, 400, rng);
  std::size_t top = 0, bottom = 0;
  for (const Vec3& n : s.normals) top += n.z() > 0.9, bottom += n.z() < -0.9;
  CHECK(top > 150);
  CHECK(bottom > 150);
  CHECK(min_sample_distance(s, 180.0) < 0.02);  // across the plate, if normals are ignored
  CHECK(min_sample_distance(s) > 0.6 * poisson_packing_distance(surface_area(plate), 400));
}

/// The smallest distance between two samples whose normals agree (dot above cos(angle)),
/// over every pair.
double brute_force_min_distance(const OrientedSamples& s, double angle_deg) {
  const double min_dot = std::cos(angle_deg * M_PI / 180.0);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      if (angle_deg >= 180.0 || s.normals[i].dot(s.normals[j]) > min_dot)
        best = std::min(best, (s.points[i] - s.points[j]).norm());
  return best;
}

TEST_CASE("min_sample_distance finds the closest agreeing pair that brute force finds", "[sampling]") {
  const SurfaceMesh fandisk = read_mesh(test::corpus_mesh("fandisk.off"));
  const SurfaceMesh plate = testing::make_box(0.5, 0.5, 0.005, 8);
  std::mt19937_64 rng(11);
  const OrientedSamples blue = sample_poisson_count(fandisk, 3000, rng);
  const OrientedSamples white = sample_uniform(fandisk, 3000, rng);
  const OrientedSamples sides = sample_poisson_count(plate, 800, rng);
  for (const double angle : {120.0, 180.0, 30.0}) {
    INFO("normal angle " << angle);
    CHECK(min_sample_distance(blue, angle) == brute_force_min_distance(blue, angle));
    CHECK(min_sample_distance(white, angle) == brute_force_min_distance(white, angle));
    CHECK(min_sample_distance(sides, angle) == brute_force_min_distance(sides, angle));
  }
  SECTION("duplicates are 0 apart") {
    OrientedSamples twice = blue;
    twice.points.push_back(blue.points[1234]);
    twice.normals.push_back(blue.normals[1234]);
    CHECK(min_sample_distance(twice) == 0.0);
  }
  SECTION("no agreeing pair: infinity") {
    OrientedSamples three;
    three.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    three.normals = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};  // 90 degrees apart
    CHECK(std::isinf(min_sample_distance(three, 60.0)));
    CHECK(min_sample_distance(three, 120.0) == 1.0);
  }
  SECTION("pairs only among samples the first probes miss") {
    // Every fourth sample (those the search probes first) has a normal of its own, spread over the
    // sphere; the rest share one: the probes have no partner within 10 degrees, and the grid widens
    // until the others meet.
    std::mt19937_64 positions(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Vec3 shared = Vec3(1, 2, 3).normalized();
    OrientedSamples mixed;
    for (int i = 0; i < 64; ++i) {
      mixed.points.push_back(Vec3(unit(positions), unit(positions), unit(positions)));
      const double z = 1 - (i / 4 + 0.5) / 8, azimuth = 2.39996 * (i / 4);  // a Fibonacci sphere of 16
      const double r = std::sqrt(1 - z * z);
      mixed.normals.push_back(i % 4 ? shared : Vec3(r * std::cos(azimuth), r * std::sin(azimuth), z));
    }
    const double min_dot = std::cos(10.0 * M_PI / 180.0);
    for (int probe = 0; probe < 64; probe += 4)
      for (int j = 0; j < 64; ++j) REQUIRE((j == probe || mixed.normals[probe].dot(mixed.normals[j]) <= min_dot));
    CHECK(std::isfinite(brute_force_min_distance(mixed, 10.0)));
    CHECK(min_sample_distance(mixed, 10.0) == brute_force_min_distance(mixed, 10.0));
  }
}

TEST_CASE("dart throwing keeps what one pass in order keeps, whatever its batches", "[sampling]") {
  // Uniform candidates of fandisk (random order, creases: normals matter) at 0.7 packing spacings
  // of 1500 samples, against the definition: each candidate kept unless a kept one before it with
  // an agreeing normal is closer than the radius.
  const SurfaceMesh fandisk = read_mesh(test::corpus_mesh("fandisk.off"));
  std::mt19937_64 rng(9);
  const OrientedSamples candidates = sample_uniform(fandisk, 15000, rng);
  const double radius = 0.7 * poisson_packing_distance(surface_area(fandisk), 1500);
  const poisson_detail::NormalRule rule(120.0);
  const auto related = [&](Index i, Index j) { return rule.agree(candidates.normals[i], candidates.normals[j]); };
  std::vector<Index> expected;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    bool free = true;
    for (std::size_t a = 0; a < expected.size() && free; ++a)
      free = !((candidates.points[expected[a]] - candidates.points[i]).squaredNorm() < radius * radius &&
               related(static_cast<Index>(i), expected[a]));
    if (free) expected.push_back(static_cast<Index>(i));
  }
  REQUIRE(expected.size() > 1000);
  for (const std::size_t every : {std::size_t{1}, std::size_t{97}, std::size_t{4096}, std::size_t{1} << 20}) {
    INFO("batches of " << every);
    std::size_t reports = 0;
    CHECK(poisson_detail::dart_throwing(candidates.points, radius, related, every, [&](double) { ++reports; }) ==
          expected);
    CHECK(reports == (candidates.size() - 1) / every);
  }
}

TEST_CASE("Poisson-disk areas follow the local spacing", "[sampling]") {
  // On a sphere the tangent-plane Voronoi cells are close to the mean area A / n.
  const SurfaceMesh sphere = testing::make_sphere(1.0, 4);
  std::mt19937_64 rng(5);
  const OrientedSamples s = sample_poisson_count(sphere, 2000, rng);
  const double mean = surface_area(sphere) / 2000.0;
  for (double a : s.areas) {
    CHECK(a > 0.4 * mean);
    CHECK(a < 1.8 * mean);
  }
}

TEST_CASE("Poisson-disk sampling is deterministic for a seed and refuses bad input", "[sampling]") {
  const SurfaceMesh mesh = testing::make_torus(1.0, 0.3, 32, 16);
  std::mt19937_64 a(11), b(11), c(12);
  const auto sa = sample_poisson_count(mesh, 500, a), sb = sample_poisson_count(mesh, 500, b);
  const auto sc = sample_poisson_count(mesh, 500, c);
  CHECK(sa.points == sb.points);
  CHECK(sa.normals == sb.normals);
  CHECK(sa.areas == sb.areas);
  CHECK(sa.points != sc.points);
  std::mt19937_64 d(11), e(11);
  CHECK(sample_poisson_radius(mesh, 0.1, d).points == sample_poisson_radius(mesh, 0.1, e).points);

  std::mt19937_64 rng(0);
  CHECK_THROWS_AS(sample_poisson_count(mesh, 0, rng), std::invalid_argument);
  CHECK_THROWS_AS(sample_poisson_radius(mesh, 0.0, rng), std::invalid_argument);
  CHECK_THROWS_AS(sample_poisson_radius(mesh, 1e-7, rng), std::invalid_argument);  // too many candidates
  SurfaceMesh flat;
  flat.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  flat.faces = {{0, 1, 2}};
  CHECK_THROWS_AS(sample_poisson_count(flat, 10, rng), std::invalid_argument);
}

TEST_CASE("Poisson-disk by count covers the surface: every point lies near a sample", "[sampling]") {
  // Coverage: 40k uniform probe points of the surface, each within the packing spacing of its
  // nearest sample (blue noise leaves no holes; measured 0.93-0.95 of the spacing here).
  for (const auto& path : {test::data_dir() / "sphere.obj", test::corpus_mesh("fandisk.off"),
                           test::corpus_mesh("turbine.off")}) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    std::mt19937_64 rng(7), probe_rng(99);
    const std::size_t n = 3000;
    const OrientedSamples s = sample_poisson_count(mesh, n, rng);
    const double spacing = poisson_packing_distance(surface_area(mesh), n);
    const PointIndex index(s.points);
    double farthest = 0;
    for (const Vec3& p : sample_uniform(mesh, 40000, probe_rng).points)
      farthest = std::max(farthest, index.nearest(p).second);
    INFO("farthest probe " << farthest / spacing << " spacings from a sample");
    CHECK(farthest <= spacing);
    CHECK(min_sample_distance(s) >= 0.65 * spacing);  // measured 0.68-0.69
  }
}

TEST_CASE("Poisson-disk sampling gives the same samples with 1 and 2 threads", "[sampling]") {
  const SurfaceMesh mesh = read_mesh(test::corpus_mesh("fandisk.off"));
  for (const bool by_radius : {false, true}) {
    OrientedSamples runs[2];
    for (int threads : {1, 2}) {
      std::mt19937_64 rng(21);
      PoissonDiskOptions options;
      options.max_threads = threads;
      runs[threads - 1] = by_radius ? sample_poisson_radius(mesh, 0.7 * poisson_packing_distance(surface_area(mesh), 20000), rng, options)
                                    : sample_poisson_count(mesh, 20000, rng, options);
    }
    CHECK(runs[0].size() > 10000);
    CHECK(runs[0].points == runs[1].points);
    CHECK(runs[0].normals == runs[1].normals);
    CHECK(runs[0].areas == runs[1].areas);
  }
}

namespace {

/// Weighted sample elimination as Yuksel 2015 states it, in the plainest form (all pairs, an
/// ordered set as the priority queue): the reference the service's grid neighbour lists and
/// elimination must reproduce bit for bit. Returns the kept candidates, ascending.
std::vector<Index> reference_elimination(const OrientedSamples& candidates, double area, std::size_t count) {
  const std::size_t m = candidates.size();
  const double r_max = poisson_packing_distance(area, count);
  const double r_min = r_max * 0.65 * (1.0 - std::pow(static_cast<double>(count) / static_cast<double>(m), 1.5));
  const double min_dot = std::cos(120.0 * 3.14159265358979323846 / 180.0);
  // Each candidate's neighbours closer than r_max with agreeing normals, closest first (ties by
  // index), and their weights.
  std::vector<std::vector<std::pair<Index, double>>> near(m);
  std::vector<double> weight(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    std::vector<std::pair<double, Index>> found;
    for (std::size_t j = 0; j < m; ++j) {
      const Vec3 d = candidates.points[i] - candidates.points[j];
      const double d2 = d.x() * d.x() + d.y() * d.y() + d.z() * d.z();
      if (j != i && std::sqrt(d2) < r_max && candidates.normals[i].dot(candidates.normals[j]) > min_dot)
        found.emplace_back(d2, static_cast<Index>(j));
    }
    std::sort(found.begin(), found.end());
    for (const auto& [d2, j] : found) {
      const double w = std::pow(1.0 - std::max(std::sqrt(d2), r_min) / r_max, 8.0);
      near[i].emplace_back(j, w);
      weight[i] += w;
    }
  }
  // Remove the heaviest (ties: the larger index) until `count` remain, lowering its neighbours.
  std::set<std::pair<double, Index>> queue;
  for (std::size_t i = 0; i < m; ++i) queue.emplace(weight[i], static_cast<Index>(i));
  std::vector<bool> removed(m, false);
  while (queue.size() > count) {
    const Index top = std::prev(queue.end())->second;
    queue.erase(std::prev(queue.end()));
    removed[top] = true;
    for (const auto& [j, w] : near[top]) {
      if (removed[j]) continue;
      queue.erase({weight[j], j});
      weight[j] -= w;
      queue.emplace(weight[j], j);
    }
  }
  std::vector<Index> kept;
  for (std::size_t i = 0; i < m; ++i)
    if (!removed[i]) kept.push_back(static_cast<Index>(i));
  return kept;
}

}  // namespace

TEST_CASE("Poisson-disk by count keeps exactly the samples of the plain sequential elimination", "[sampling]") {
  // Small inputs where an all-pairs search is cheap; 1, 2 and 4 threads. A torus (curved, with
  // the normal rule at work across its hole) and fandisk (sharp edges, flat regions where many
  // weights are equal).
  const std::vector<std::pair<SurfaceMesh, std::size_t>> cases = {
      {testing::make_torus(1.0, 0.3, 32, 16), 300}, {read_mesh(test::corpus_mesh("fandisk.off")), 400}};
  for (const auto& [mesh, count] : cases) {
    for (std::uint64_t seed : {1u, 2u}) {
      std::mt19937_64 candidate_rng(seed);
      const OrientedSamples candidates = sample_uniform(mesh, 5 * count, candidate_rng);
      const std::vector<Index> kept = reference_elimination(candidates, surface_area(mesh), count);
      for (int threads : {1, 2, 4}) {
        INFO("count " << count << ", seed " << seed << ", " << threads << " threads");
        std::mt19937_64 rng(seed);
        PoissonDiskOptions options;
        options.max_threads = threads;
        const OrientedSamples s = sample_poisson_count(mesh, count, rng, options);
        REQUIRE(s.size() == kept.size());
        std::size_t same = 0;
        for (std::size_t k = 0; k < kept.size(); ++k)
          same += s.points[k] == candidates.points[kept[k]] && s.normals[k] == candidates.normals[kept[k]];
        CHECK(same == kept.size());
      }
    }
  }
}

TEST_CASE("Poisson-disk areas: the grid search gives the k-d tree's areas bit for bit", "[sampling]") {
  // The areas clip each sample's tangent cell by its 16 nearest samples in a k-d tree's order; a
  // grid finds them where it can vouch for the same list. Tiny cells send every sample through
  // the k-d tree, 2 spacings part of them, 4 spacings nearly none.
  const SurfaceMesh mesh = read_mesh(test::corpus_mesh("fandisk.off"));
  const double area = surface_area(mesh);
  std::mt19937_64 rng(3);
  const OrientedSamples s = sample_poisson_count(mesh, 3000, rng);
  const double bound = 0.75 * poisson_packing_distance(area, 3000);
  const poisson_detail::NormalRule rule(120.0);
  const std::vector<double> kdtree = poisson_detail::tangent_voronoi_areas(s, area, bound, rule, 1e-3);
  CHECK(kdtree == s.areas);
  for (double cells : {2.0, 4.0}) {
    INFO(cells << " spacings");
    CHECK(poisson_detail::tangent_voronoi_areas(s, area, bound, rule, cells) == kdtree);
  }
}

TEST_CASE("Uniform samples: the face guide table picks the faces a binary search picks", "[sampling]") {
  // sample_uniform finds each draw's face through buckets of cumulative area; the reference
  // draws the same numbers and runs std::upper_bound over all faces. Meshes with faces of very
  // different areas (fandisk) and many small ones (a fine sphere).
  for (const SurfaceMesh& mesh : {read_mesh(test::corpus_mesh("fandisk.off")), testing::make_sphere(1.0, 5)}) {
    std::vector<double> cumulative = face_areas(mesh);
    std::partial_sum(cumulative.begin(), cumulative.end(), cumulative.begin());
    std::mt19937_64 rng(17), reference_rng(17);
    const std::size_t n = 20000;
    const OrientedSamples s = sample_uniform(mesh, n, rng);
    std::size_t same = 0;
    for (std::size_t k = 0; k < n; ++k) {
      double draw[3];
      for (double& x : draw) x = static_cast<double>(reference_rng() >> 11) * 0x1.0p-53;
      const auto f = std::min<std::size_t>(
          static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), draw[0] * cumulative.back()) -
                                   cumulative.begin()),
          mesh.faces.size() - 1);
      double u = draw[1], v = draw[2];
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const auto& [a, b, c] = mesh.faces[f];
      const Vec3 p =
          mesh.vertices[a] + u * (mesh.vertices[b] - mesh.vertices[a]) + v * (mesh.vertices[c] - mesh.vertices[a]);
      same += p == s.points[k];
    }
    CHECK(same == n);
  }
}

TEST_CASE("Dart throwing over grid phases: separated, maximal, the same with any thread count", "[sampling]") {
  // Candidates on a torus (curved, normals opposite across its hole) and fandisk (creases); every
  // pair checked by brute force.
  const poisson_detail::NormalRule rule(120.0);
  for (const SurfaceMesh& mesh : {testing::make_torus(1.0, 0.3, 32, 16), read_mesh(test::corpus_mesh("fandisk.off"))}) {
    std::mt19937_64 rng(4);
    const OrientedSamples candidates = sample_uniform(mesh, 6000, rng);
    const double radius = 0.6 * poisson_packing_distance(surface_area(mesh), 1000);
    const poisson_detail::DartThrower darts(candidates.points, candidates.normals, 4 * radius);
    const std::vector<Index> kept = darts.kept(radius, rule);
    REQUIRE(std::is_sorted(kept.begin(), kept.end()));
    std::vector<bool> is_kept(candidates.size(), false);
    for (Index i : kept) is_kept[i] = true;
    const auto repel = [&](std::size_t i, std::size_t j) {
      return (candidates.points[i] - candidates.points[j]).squaredNorm() < radius * radius &&
             rule.agree(candidates.normals[i], candidates.normals[j]);
    };
    std::size_t too_close = 0, uncovered = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      bool covered = is_kept[i];
      for (Index j : kept) {
        if (j == i || !repel(i, j)) continue;
        too_close += is_kept[i];
        covered = true;
      }
      uncovered += !covered;
    }
    CHECK(too_close == 0);
    CHECK(uncovered == 0);
    CHECK(kept.size() > 500);
    for (int threads : {1, 2, 4}) {
      tbb::task_arena arena(threads);
      CHECK(arena.execute([&] { return darts.kept(radius, rule); }) == kept);
    }
    // A smaller radius from the same grid keeps more.
    CHECK(darts.kept(0.8 * radius, rule).size() > kept.size());
  }
}

TEST_CASE("Poisson-disk from dart-thrown candidates: exact count, blue noise, coverage, thread-independent",
          "[sampling]") {
  // candidates: darts. The samples keep the darts' radius: 0.65 spacings, or a little less where
  // the candidates do not give `count` darts there (measured 0.65 on sphere, 0.64 on fandisk and
  // turbine, against the uniform candidates' 0.68-0.70). No holes: every probe within 1.05
  // spacings of a sample (measured 0.94-1.00, against the uniform candidates' 0.93-0.95; uniform
  // random samples leave holes of several spacings).
  for (const auto& path : {test::data_dir() / "sphere.obj", test::corpus_mesh("fandisk.off"),
                           test::corpus_mesh("turbine.off")}) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    const std::size_t n = 3000;
    const double spacing = poisson_packing_distance(surface_area(mesh), n);
    OrientedSamples runs[2];
    for (int threads : {1, 2}) {
      std::mt19937_64 rng(7);
      PoissonDiskOptions options;
      options.candidates = PoissonCandidates::Darts;
      options.max_threads = threads;
      runs[threads - 1] = sample_poisson_count(mesh, n, rng, options);
    }
    const OrientedSamples& s = runs[0];
    REQUIRE(s.size() == n);
    check_on_surface(mesh, s);
    CHECK(runs[1].points == s.points);
    CHECK(runs[1].areas == s.areas);
    const double min_distance = min_sample_distance(s);
    INFO("minimum distance " << min_distance / spacing << " spacings");
    CHECK(min_distance >= 0.6 * spacing);
    std::mt19937_64 probe_rng(99);
    const PointIndex index(s.points);
    double farthest = 0;
    for (const Vec3& p : sample_uniform(mesh, 40000, probe_rng).points)
      farthest = std::max(farthest, index.nearest(p).second);
    INFO("farthest probe " << farthest / spacing << " spacings from a sample");
    CHECK(farthest <= 1.05 * spacing);
  }
}

TEST_CASE("Poisson-disk sampling reports its progress and stops when the report throws", "[sampling]") {
  // 30k samples by count (120k removals) and a radius giving ~200k candidates: enough for the
  // periodic reports of the elimination and of the dart throwing.
  const SurfaceMesh mesh = read_mesh(test::corpus_mesh("fandisk.off"));
  const double radius = 0.7 * poisson_packing_distance(surface_area(mesh), 20000);
  struct Stop {};
  const std::vector<std::pair<std::string, PoissonCandidates>> modes{
      {"count", PoissonCandidates::Uniform}, {"count", PoissonCandidates::Darts}, {"radius", PoissonCandidates::Uniform}};
  for (const auto& [mode, candidates] : modes) {
    INFO(mode << (candidates == PoissonCandidates::Darts ? ", darts" : ""));
    const std::string loop = mode == "count" ? "elimination" : "dart throwing";
    PoissonDiskOptions options;
    options.candidates = candidates;
    const auto sample = [&] {
      std::mt19937_64 rng(8);
      return mode == "count" ? sample_poisson_count(mesh, 30000, rng, options)
                             : sample_poisson_radius(mesh, radius, rng, options);
    };
    std::vector<std::pair<double, std::string>> reports;
    options.progress = [&](double fraction, std::string_view phase) { reports.emplace_back(fraction, phase); };
    const OrientedSamples s = sample();
    REQUIRE(reports.size() > 3);
    for (std::size_t k = 1; k < reports.size(); ++k) CHECK(reports[k].first >= reports[k - 1].first);
    CHECK(reports.back() == std::make_pair(1.0, std::string("areas")));
    // At least one report from inside the long loop, before its end (the darts leave the
    // elimination a few hundred removals: only its end is reported).
    const long inside = candidates == PoissonCandidates::Darts ? 0 : 1;
    CHECK(std::count_if(reports.begin(), reports.end(), [&](const auto& r) { return r.second == loop; }) >= 1 + inside);
    options.progress = [&](double, std::string_view phase) {
      if (phase == loop) throw Stop{};
    };
    CHECK_THROWS_AS(sample(), Stop);
    options.progress = {};
    CHECK(sample().points == s.points);  // reporting changes nothing
  }
}
