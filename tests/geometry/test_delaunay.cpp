// medax::services::delaunay_tetrahedralize against configurations with known answers, and the
// invariants every Delaunay tetrahedralization has (empty spheres, symmetric adjacency, Euler
// characteristic of a ball, determinism).
#include <medax/services/delaunay.hpp>

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <stdexcept>

using namespace medax;
using services::DelaunayTetrahedralization;
using services::delaunay_tetrahedralize;

namespace {

double signed_volume(const std::vector<Vec3>& p, const std::array<Index, 4>& c) {
  return (p[c[1]] - p[c[0]]).dot((p[c[2]] - p[c[0]]).cross(p[c[3]] - p[c[0]])) / 6.0;
}

std::vector<Vec3> random_points(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<Vec3> p(n);
  for (Vec3& x : p) x = Vec3(u(), u(), u());
  return p;
}

/// Adjacency is symmetric, every finite cell is positively oriented, and every corner of a
/// cell is at the circumradius from its circumcentre.
void check_structure(const std::vector<Vec3>& points, const DelaunayTetrahedralization& dt) {
  for (std::size_t c = 0; c < dt.cells.size(); ++c) {
    CHECK(signed_volume(points, dt.cells[c]) > 0);
    for (Index v : dt.cells[c])
      CHECK((points[v] - dt.circumcentres[c]).norm() == Approx(dt.circumradii[c]).epsilon(1e-9));
    for (int k = 0; k < 4; ++k) {
      const std::int64_t n = dt.neighbours[c][k];
      if (n == DelaunayTetrahedralization::kInfinite) continue;
      REQUIRE(n >= 0);
      REQUIRE(static_cast<std::size_t>(n) < dt.cells.size());
      const auto& back = dt.neighbours[n];
      CHECK(std::count(back.begin(), back.end(), static_cast<std::int64_t>(c)) == 1);
      // The shared facet: the three corners other than k are corners of n.
      for (int i = 0; i < 4; ++i)
        if (i != k) CHECK(std::count(dt.cells[n].begin(), dt.cells[n].end(), dt.cells[c][i]) == 1);
      CHECK(std::count(dt.cells[n].begin(), dt.cells[n].end(), dt.cells[c][k]) == 0);
    }
  }
}

}  // namespace

TEST_CASE("Delaunay of one tetrahedron: one cell, known circumsphere, all neighbours infinite", "[geometry][delaunay]") {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const auto dt = delaunay_tetrahedralize(p);
  REQUIRE(dt.cells.size() == 1);
  std::array<Index, 4> corners = dt.cells[0];
  std::sort(corners.begin(), corners.end());
  CHECK(corners == std::array<Index, 4>{0, 1, 2, 3});
  for (std::int64_t n : dt.neighbours[0]) CHECK(n == DelaunayTetrahedralization::kInfinite);
  CHECK((dt.circumcentres[0] - Vec3(0.5, 0.5, 0.5)).norm() < 1e-15);
  CHECK(dt.circumradii[0] == Approx(std::sqrt(3.0) / 2).epsilon(1e-15));
  CHECK(dt.vertex_point == std::vector<Index>{0, 1, 2, 3});
  check_structure(p, dt);
}

TEST_CASE("Delaunay of cube corners and centre: 12 cells around the centre", "[geometry][delaunay]") {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  p.emplace_back(0, 0, 0);
  const auto dt = delaunay_tetrahedralize(p);
  // The corners are cospherical with the centre inside their sphere: the tetrahedralization is
  // the centre joined to the two triangles of each square face.
  REQUIRE(dt.cells.size() == 12);
  double volume = 0;
  std::map<std::array<long, 3>, int> per_face;
  for (std::size_t c = 0; c < dt.cells.size(); ++c) {
    CHECK(std::count(dt.cells[c].begin(), dt.cells[c].end(), Index{8}) == 1);
    volume += signed_volume(p, dt.cells[c]);
    // Circumcentre 1.5 along the face's outward axis, radius 1.5.
    const Vec3& cc = dt.circumcentres[c];
    CHECK(dt.circumradii[c] == Approx(1.5).epsilon(1e-12));
    CHECK(cc.norm() == Approx(1.5).epsilon(1e-12));
    CHECK(cc.cwiseAbs().maxCoeff() == Approx(1.5).epsilon(1e-12));
    ++per_face[{std::lround(cc.x()), std::lround(cc.y()), std::lround(cc.z())}];
  }
  CHECK(volume == Approx(8.0).epsilon(1e-12));
  CHECK(per_face.size() == 6);
  for (const auto& [axis, n] : per_face) CHECK(n == 2);
  check_structure(p, dt);
}

TEST_CASE("Delaunay merges duplicate points onto their lowest index", "[geometry][delaunay]") {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 0}, {0, 0, 1}};
  const auto dt = delaunay_tetrahedralize(p);
  CHECK(dt.vertex_point == std::vector<Index>{0, 1, 2, 4});
  REQUIRE(dt.point_vertex.size() == p.size());
  CHECK(dt.point_vertex[3] == dt.point_vertex[1]);
  CHECK(dt.point_vertex[5] == dt.point_vertex[0]);
  CHECK(dt.point_vertex[6] == dt.point_vertex[4]);
  for (std::size_t i = 0; i < p.size(); ++i) CHECK(p[dt.vertex_point[dt.point_vertex[i]]] == p[i]);
  REQUIRE(dt.cells.size() == 1);
  std::array<Index, 4> corners = dt.cells[0];
  std::sort(corners.begin(), corners.end());
  CHECK(corners == std::array<Index, 4>{0, 1, 2, 4});
}

TEST_CASE("Delaunay refuses points that do not span three dimensions", "[geometry][delaunay]") {
  std::vector<Vec3> plane;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) plane.emplace_back(i, j, 0.5 * i - 0.25 * j);
  CHECK_THROWS_AS(delaunay_tetrahedralize(plane), std::invalid_argument);
  const std::vector<Vec3> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  CHECK_THROWS_AS(delaunay_tetrahedralize(line), std::invalid_argument);
  const std::vector<Vec3> same{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  CHECK_THROWS_AS(delaunay_tetrahedralize(same), std::invalid_argument);
  CHECK_THROWS_AS(delaunay_tetrahedralize({}), std::invalid_argument);
}

TEST_CASE("Delaunay of random points: empty spheres, a ball's Euler characteristic, determinism",
          "[geometry][delaunay]") {
  const auto p = random_points(400, 7);
  const auto dt = delaunay_tetrahedralize(p);
  REQUIRE(!dt.cells.empty());
  check_structure(p, dt);
  // Empty circumspheres (up to rounding): no point strictly inside any circumsphere.
  std::size_t violations = 0;
  for (std::size_t c = 0; c < dt.cells.size(); ++c)
    for (const Vec3& q : p)
      if ((q - dt.circumcentres[c]).norm() < dt.circumradii[c] * (1 - 1e-9)) ++violations;
  CHECK(violations == 0);
  // V - E + F - T = 1 for a triangulated ball; the hull facets have infinite neighbours.
  std::set<std::pair<Index, Index>> edges;
  std::set<std::array<Index, 3>> facets;
  for (const auto& c : dt.cells) {
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges.insert(std::minmax(c[i], c[j]));
    for (int k = 0; k < 4; ++k) {
      std::array<Index, 3> f;
      for (int i = 0, n = 0; i < 4; ++i)
        if (i != k) f[n++] = c[i];
      std::sort(f.begin(), f.end());
      facets.insert(f);
    }
  }
  const long euler = static_cast<long>(dt.vertex_point.size()) - static_cast<long>(edges.size()) +
                     static_cast<long>(facets.size()) - static_cast<long>(dt.cells.size());
  CHECK(euler == 1);
  // Same input, same output; sequential and parallel give the same arrays.
  const auto again = delaunay_tetrahedralize(p);
  const auto sequential = delaunay_tetrahedralize(p, {false});
  for (const auto* other : {&again, &sequential}) {
    CHECK(other->cells == dt.cells);
    CHECK(other->neighbours == dt.neighbours);
    CHECK(other->circumcentres == dt.circumcentres);
    CHECK(other->circumradii == dt.circumradii);
  }
}

TEST_CASE("Delaunay with more than 10k points (the former parallel path) is valid and deterministic",
          "[geometry][delaunay]") {
  const auto p = random_points(12000, 11);
  const auto dt = delaunay_tetrahedralize(p);
  const auto sequential = delaunay_tetrahedralize(p, {false});
  CHECK(dt.cells == sequential.cells);
  CHECK(dt.neighbours == sequential.neighbours);
  double volume = 0;
  std::size_t hull_facets = 0;
  for (std::size_t c = 0; c < dt.cells.size(); ++c) {
    volume += signed_volume(p, dt.cells[c]);
    for (std::int64_t n : dt.neighbours[c]) hull_facets += n == DelaunayTetrahedralization::kInfinite;
  }
  // The hull of 12k uniform points fills most of the unit cube; the facets of a closed
  // triangulated hull surface satisfy F = 2V_hull - 4 > 0.
  CHECK(volume > 0.97);
  CHECK(volume <= 1.0);
  CHECK(hull_facets > 0);
}

TEST_CASE("Delaunay alongside other work: both run and failures of either propagate", "[geometry][delaunay]") {
  const std::vector<Vec3> tetrahedron{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const bool parallel : {true, false}) {
    bool ran = false;
    const auto dt = services::delaunay_tetrahedralize_alongside(tetrahedron, {parallel}, [&] { ran = true; });
    CHECK(ran);
    CHECK(dt.cells.size() == 1);
    CHECK_THROWS_WITH(services::delaunay_tetrahedralize_alongside(
                          tetrahedron, {parallel}, [] { throw std::runtime_error("setup failed"); }),
                      "setup failed");
    const std::vector<Vec3> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    bool flat_ran = false;
    CHECK_THROWS_AS(services::delaunay_tetrahedralize_alongside(flat, {parallel}, [&] { flat_ran = true; }),
                    std::invalid_argument);
    CHECK(flat_ran);  // the other work was waited for before the error left
  }
}

namespace {

/// Every array of the two tetrahedralizations is identical.
void check_identical(const DelaunayTetrahedralization& a, const DelaunayTetrahedralization& b) {
  CHECK(a.vertex_point == b.vertex_point);
  CHECK(a.point_vertex == b.point_vertex);
  CHECK(a.cells == b.cells);
  CHECK(a.neighbours == b.neighbours);
  CHECK(a.circumcentres == b.circumcentres);
  CHECK(a.circumradii == b.circumradii);
}

/// The tetrahedralization with 1, 2 and 4 threads and without TBB (inputs of 50k points or more
/// take the concurrent path, whose last insertion rounds go in concurrently).
void check_thread_independent(const std::vector<Vec3>& p) {
  const auto two = delaunay_tetrahedralize(p, {true, 2});
  const auto one = delaunay_tetrahedralize(p, {true, 1});
  const auto again = delaunay_tetrahedralize(p, {true, 2});
  const auto four = delaunay_tetrahedralize(p, {true, 4});
  const auto sequential = delaunay_tetrahedralize(p, {false});
  check_identical(two, one);
  check_identical(two, again);
  check_identical(two, four);
  check_identical(two, sequential);
}

}  // namespace

TEST_CASE("Concurrent Delaunay of random points: valid, identical across runs and thread counts",
          "[geometry][delaunay]") {
  const auto p = random_points(60000, 13);
  const auto dt = delaunay_tetrahedralize(p, {true, 2});
  check_structure(p, dt);
  // Canonical corners: the smallest index first, positively oriented.
  for (const auto& c : dt.cells) CHECK(*std::min_element(c.begin(), c.end()) == c[0]);
  check_thread_independent(p);
}

TEST_CASE("Concurrent Delaunay of a cubic lattice (every cube cospherical): one answer whatever the threads",
          "[geometry][delaunay]") {
  // 38^3 lattice points: each unit cube's 8 corners are cospherical, so the tetrahedralization is
  // only defined by CGAL's symbolic perturbation; it must not depend on who inserted what first.
  std::vector<Vec3> p;
  for (int i = 0; i < 38; ++i)
    for (int j = 0; j < 38; ++j)
      for (int k = 0; k < 38; ++k) p.emplace_back(i, j, k);
  const auto dt = delaunay_tetrahedralize(p, {true, 2});
  double volume = 0;
  std::size_t flat = 0;
  for (const auto& c : dt.cells) {
    const double v = signed_volume(p, c);
    volume += v;
    flat += !(v > 0);
  }
  CHECK(flat == 0);
  CHECK(volume == Approx(37.0 * 37.0 * 37.0).epsilon(1e-9));
  check_thread_independent(p);
}

TEST_CASE("Concurrent Delaunay of surface samples (a sphere): identical across thread counts", "[geometry][delaunay]") {
  // Points on a surface, as the Voronoi methods triangulate them: nearly cospherical everywhere.
  std::mt19937_64 rng(17);
  std::normal_distribution<double> gauss;
  std::vector<Vec3> p(60000);
  for (Vec3& x : p) x = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
  check_thread_independent(p);
}

TEST_CASE("Delaunay numbers cells by their sorted corners below 50k points", "[geometry][delaunay]") {
  const auto p = random_points(3000, 19);
  const auto dt = delaunay_tetrahedralize(p);
  std::vector<std::array<Index, 4>> sorted;
  for (auto c : dt.cells) {
    std::sort(c.begin(), c.end());
    sorted.push_back(c);
  }
  for (std::size_t c = 1; c < sorted.size(); ++c) CHECK(sorted[c - 1] < sorted[c]);
}

TEST_CASE("Concurrent Delaunay numbers cells along space, whatever the order of the points", "[geometry][delaunay]") {
  // Points in random order: numbered by their corners' point indices, one cell in seven or so
  // would jump to a random place of the cube; numbered along the insertion's space-filling
  // curve, consecutive cells are neighbours in space (and in memory, for whoever walks them).
  const auto p = random_points(60000, 23);
  const auto dt = delaunay_tetrahedralize(p, {true, 2});
  const auto centroid = [&](const std::array<Index, 4>& c) { return (p[c[0]] + p[c[1]] + p[c[2]] + p[c[3]]) / 4; };
  std::size_t jumps = 0;  // consecutive cells farther apart than about four point spacings (0.025)
  for (std::size_t c = 1; c < dt.cells.size(); ++c) jumps += (centroid(dt.cells[c]) - centroid(dt.cells[c - 1])).norm() > 0.1;
  CHECK(jumps < dt.cells.size() / 100);
}

TEST_CASE("Concurrent Delaunay under a global one-thread limit: the same tetrahedralization", "[geometry][delaunay]") {
  const auto p = random_points(60000, 29);
  const auto two = delaunay_tetrahedralize(p, {true, 2});
  const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  check_identical(two, delaunay_tetrahedralize(p));
}

TEST_CASE("Concurrent Delaunay merges duplicates onto their lowest index, whatever the threads", "[geometry][delaunay]") {
  // 60k random points, then every 37th point again at the end and point 5 once more in front of
  // it: the copies share their original's vertex, which is named by the lowest index.
  auto p = random_points(60000, 31);
  for (std::size_t i = 0; i < 60000; i += 37) p.push_back(p[i]);
  p[100] = p[5];
  const auto dt = delaunay_tetrahedralize(p, {true, 2});
  CHECK(dt.vertex_point.size() == 60000 - 1);  // p[100] merged into p[5]
  CHECK(dt.point_vertex[100] == dt.point_vertex[5]);
  CHECK(dt.vertex_point[dt.point_vertex[100]] == 5);
  for (std::size_t i = 60000; i < p.size(); ++i) {
    const Index original = static_cast<Index>((i - 60000) * 37);
    CHECK(dt.point_vertex[i] == dt.point_vertex[original]);
    CHECK(dt.vertex_point[dt.point_vertex[i]] == original);
  }
  for (std::size_t i = 0; i < p.size(); ++i) CHECK(p[dt.vertex_point[dt.point_vertex[i]]] == p[i]);
  check_structure(p, dt);
  check_thread_independent(p);
}
