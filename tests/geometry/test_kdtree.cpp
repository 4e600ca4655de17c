// PointIndex (nanoflann k-d tree) against brute force.
#include <medax/services/kdtree.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

using namespace medax;

namespace {

std::vector<Vec3> random_points(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<Vec3> out(n);
  for (Vec3& p : out) p = Vec3(u(), u(), u());
  return out;
}

/// All points by distance to q (ties by index).
std::vector<std::pair<Index, double>> by_distance(const std::vector<Vec3>& points, const Vec3& q) {
  std::vector<std::pair<Index, double>> all(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) all[i] = {static_cast<Index>(i), (points[i] - q).norm()};
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second < b.second : a.first < b.first;
  });
  return all;
}

}  // namespace

TEST_CASE("PointIndex nearest, k-nearest and radius queries match brute force", "[geometry][kdtree]") {
  const auto points = random_points(3000, 3);
  const services::PointIndex index(points);
  CHECK(&index.points() == &points);
  for (const Vec3& q : random_points(100, 4)) {
    const auto truth = by_distance(points, q);
    const auto [nearest, d] = index.nearest(q);
    CHECK(d == Approx(truth[0].second).epsilon(1e-12));
    CHECK((points[nearest] - q).norm() == Approx(truth[0].second).epsilon(1e-12));

    const auto knn = index.k_nearest(q, 10);
    REQUIRE(knn.size() == 10);
    for (std::size_t i = 0; i < knn.size(); ++i) {
      CHECK(knn[i].second == Approx(truth[i].second).epsilon(1e-12));
      CHECK((points[knn[i].first] - q).norm() == Approx(knn[i].second).epsilon(1e-12));
      if (i > 0) CHECK(knn[i - 1].second <= knn[i].second);
    }

    const double radius = 0.1;
    const auto within = index.within(q, radius);
    std::vector<Index> expected, got;
    for (const auto& [i, dist] : truth)
      if (dist < radius) expected.push_back(i);
    for (const auto& [i, dist] : within) {
      got.push_back(i);
      CHECK(dist == Approx((points[i] - q).norm()).epsilon(1e-12));
    }
    for (std::size_t i = 1; i < within.size(); ++i) CHECK(within[i - 1].second <= within[i].second);
    std::sort(expected.begin(), expected.end());
    std::sort(got.begin(), got.end());
    CHECK(got == expected);
  }
}

TEST_CASE("PointIndex with fewer points than k returns them all", "[geometry][kdtree]") {
  const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  const services::PointIndex index(points);
  const auto knn = index.k_nearest(Vec3(0.1, 0, 0), 5);
  REQUIRE(knn.size() == 3);
  CHECK(knn[0].first == 0);
  CHECK(knn[1].first == 1);
  CHECK(knn[2].first == 2);
  CHECK(knn[0].second == Approx(0.1));
}
