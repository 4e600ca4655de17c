// Poles, umbrellas and the two conditions (notes §2.1, §2.5, §4.3.2): pole vectors and umbrella
// triangles approach the surface normals as the sampling gets denser, an umbrella edge never
// passes a condition at its end and is never selected, an empty umbrella selects nothing.
#include "fixtures.hpp"

#include <medax/services/delaunay.hpp>

#include <catch2/catch.hpp>

#include <set>

using namespace medax;
using dz_test::quantile;

namespace {

/// Largest angle between a point's pole vector (or an umbrella normal) and the exact normal, and
/// largest umbrella circumradius over the local feature size.
struct UmbrellaQuality {
  double pole_angle = 0, normal_angle = 0, radius_over_lfs = 0;
  std::size_t small_bounded = 0, bounded = 0;
};

template <typename Lfs>
UmbrellaQuality quality(const dz_test::Sampled& s, const Lfs& lfs) {
  const auto dt = services::delaunay_tetrahedralize(s.points);
  const auto u = dey_zhao::compute_umbrellas(s.points, dt, true);
  UmbrellaQuality q;
  for (Index x = 0; x < s.points.size(); ++x) {
    const Vec3& n = s.normals[x];
    q.pole_angle = std::max(q.pole_angle, std::acos(std::min(1.0, std::abs(u.pole_vector[x].dot(n)))));
    for (std::size_t i = u.offsets[x]; i < u.offsets[x + 1]; ++i) {
      q.normal_angle = std::max(q.normal_angle, std::acos(std::min(1.0, std::abs(u.normals[i].dot(n)))));
      const auto& t = u.triangles[i];
      CHECK((t[0] == x || t[1] == x || t[2] == x));  // umbrella triangles are incident to their point
    }
    q.radius_over_lfs = std::max(q.radius_over_lfs, u.max_radius[x] / lfs(s.points[x]));
    if (!u.on_hull[x]) {
      ++q.bounded;
      if (u.size(x) < 3) ++q.small_bounded;
    }
  }
  return q;
}

}  // namespace

TEST_CASE("dey_zhao umbrellas: pole vectors and umbrella normals approach the surface normals", "[dey_zhao][umbrella]") {
  // Notes §4.3.2: max angle(v_p, n_p), max angle(n_ptu, n_p) and max R / f decrease with N.
  // The ellipsoid has only unbounded cells (every sample is on the hull); the torus has both.
  const double a = 1.0, b = 0.7, c = 0.4;
  std::vector<UmbrellaQuality> e, t;
  for (std::size_t n : {2000, 8000, 32000}) {
    e.push_back(quality(dz_test::ellipsoid(a, b, c, n),
                        [&](const Vec3& p) { return testing::ellipsoid_axis_distance(p, a, b, c); }));
    // torus: f = distance to the core circle (inner axis) or to the z axis (outer axis)
    t.push_back(quality(dz_test::torus(1.0, 0.35, n), [&](const Vec3& p) {
      return std::min(testing::torus_axis_distance(p, 1.0), Vec3(p.x(), p.y(), 0).norm());
    }));
  }
  for (std::size_t i = 0; i < 3; ++i) {
    INFO("level " << i << ": ellipsoid pole " << e[i].pole_angle << " normal " << e[i].normal_angle << " R/f "
                  << e[i].radius_over_lfs << "; torus pole " << t[i].pole_angle << " normal " << t[i].normal_angle
                  << " R/f " << t[i].radius_over_lfs);
    CHECK(e[i].bounded == 0);
    CHECK(t[i].bounded > 0);
    CHECK(t[i].small_bounded == 0);  // a bounded cell has a closed fan of at least 3 triangles
    if (i > 0) {
      CHECK(e[i].pole_angle < e[i - 1].pole_angle);
      CHECK(e[i].normal_angle < e[i - 1].normal_angle);
      CHECK(e[i].radius_over_lfs < e[i - 1].radius_over_lfs);
      CHECK(t[i].pole_angle < t[i - 1].pole_angle);
      CHECK(t[i].normal_angle < t[i - 1].normal_angle);
      CHECK(t[i].radius_over_lfs < t[i - 1].radius_over_lfs);
    }
  }
  CHECK(e[2].pole_angle < 0.05);
  CHECK(t[2].normal_angle < 0.2);
}

TEST_CASE("dey_zhao umbrellas: umbrella edges fail both conditions at their end and are never selected",
          "[dey_zhao][umbrella]") {
  for (int shape = 0; shape < 2; ++shape) {
    const dz_test::Sampled s = shape ? dz_test::torus(1.0, 0.35, 8000) : dz_test::ellipsoid(1.0, 0.7, 0.4, 8000);
    const auto dt = services::delaunay_tetrahedralize(s.points);
    const auto u = dey_zhao::compute_umbrellas(s.points, dt, true);
    std::set<std::pair<Index, Index>> umbrella_edges;
    std::size_t passing = 0, checked = 0;
    for (Index x = 0; x < s.points.size(); ++x)
      for (std::size_t i = u.offsets[x]; i < u.offsets[x + 1]; ++i)
        for (Index y : u.triangles[i]) {
          if (y == x) continue;
          const Index p = std::min(x, y), q = std::max(x, y);
          umbrella_edges.insert({p, q});
          // §2.5: its angle to that triangle's plane is 0 and |pq| <= 2R < rho R.
          const int bits = dey_zhao::conditions(dey_zhao::score_edge(s.points, u, p, q), {});
          const int at_x = x == p ? (dey_zhao::kAngleP | dey_zhao::kRatioP) : (dey_zhao::kAngleQ | dey_zhao::kRatioQ);
          passing += (bits & at_x) != 0;
          ++checked;
        }
    CHECK(checked > 6 * s.points.size());
    CHECK(passing == 0);
    // ... and no output facet, inner or outer, is dual to an umbrella edge (of either end).
    dey_zhao::MedialReport report;
    const MedialComplex m = dz_test::run(s, dz_test::with_inner(dey_zhao::InnerSelection::None), &report);
    REQUIRE(!m.faces.empty());
    const auto& P = m.get(dey_zhao::kDualP);
    const auto& Q = m.get(dey_zhao::kDualQ);
    std::size_t dual = 0;
    for (std::size_t f = 0; f < m.faces.size(); ++f)
      dual += umbrella_edges.count({static_cast<Index>(P[f]), static_cast<Index>(Q[f])});
    CHECK(dual == 0);
  }
}

TEST_CASE("dey_zhao umbrellas: an empty umbrella selects nothing", "[dey_zhao][umbrella]") {
  dey_zhao::MedialOptions o;
  // Both ends empty: no condition, whatever the thresholds.
  CHECK(dey_zhao::conditions({}, o) == 0);
  o.theta = 0;
  o.rho = 0;
  CHECK(dey_zhao::conditions({}, o) == 0);
  // One end empty: only the other end's bits.
  dey_zhao::EdgeScores one;
  one.sin_angle_q = 1;
  one.ratio_q = 100;
  CHECK(dey_zhao::conditions(one, {}) == (dey_zhao::kAngleQ | dey_zhao::kRatioQ));

  // Empty the umbrella of one torus sample: every edge at it loses that end's bits, and the
  // edges whose other end has an empty umbrella too are not selected at all.
  const dz_test::Sampled s = dz_test::torus(1.0, 0.35, 2000);
  const auto dt = services::delaunay_tetrahedralize(s.points);
  dey_zhao::Umbrellas u = dey_zhao::compute_umbrellas(s.points, dt, true);
  const Index x = 17;
  REQUIRE(u.size(x) > 0);
  const std::size_t removed = u.size(x);
  u.normals.erase(u.normals.begin() + static_cast<std::ptrdiff_t>(u.offsets[x]),
                  u.normals.begin() + static_cast<std::ptrdiff_t>(u.offsets[x + 1]));
  for (std::size_t i = x + 1; i < u.offsets.size(); ++i) u.offsets[i] -= removed;
  REQUIRE(u.size(x) == 0);
  std::set<Index> neighbours;
  for (const auto& cell : dt.cells)
    if (std::find(cell.begin(), cell.end(), x) != cell.end())
      for (Index y : cell)
        if (y != x) neighbours.insert(y);
  REQUIRE(neighbours.size() > 5);
  dey_zhao::MedialOptions loose;  // would select nearly everything at a non-empty end
  loose.theta = 0;
  loose.rho = 0;
  for (Index y : neighbours) {
    const Index p = std::min(x, y), q = std::max(x, y);
    const dey_zhao::EdgeScores sc = dey_zhao::score_edge(s.points, u, p, q);
    const int at_x = x == p ? (dey_zhao::kAngleP | dey_zhao::kRatioP) : (dey_zhao::kAngleQ | dey_zhao::kRatioQ);
    CHECK((x == p ? sc.sin_angle_p : sc.sin_angle_q) == -1);
    CHECK((x == p ? sc.ratio_p : sc.ratio_q) == -1);
    CHECK((dey_zhao::conditions(sc, loose) & at_x) == 0);
  }
}
