// The joining steps of MSD's refinement (plugins/msd/refine_stitch) on rings of a sphere around a
// vertex element: the band between a patch border and a template border, and the cap of a
// border with nothing to join, are made of consistent triangles that use each border edge once,
// reversed.
#include "refine_stitch.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <utility>

using namespace medax;
using namespace medax::msd::refine;

namespace {

/// A ring of n points at polar angle `polar` on the sphere of radius `radius` around the origin,
/// walked east (counter-clockwise seen from +z) or west; appended to `points`, ids returned.
std::vector<Index> ring(std::vector<FramedPoint>& points, int n, double polar, double radius, bool east, double phase) {
  std::vector<Index> ids;
  for (int k = 0; k < n; ++k) {
    const double azimuth = (east ? 1 : -1) * 2 * M_PI * k / n + phase;
    const Vec3 d(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
    ids.push_back(static_cast<Index>(points.size()));
    points.push_back({radius * d, Vec3::Zero(), 0.5 * d});
  }
  return ids;
}

std::set<std::pair<Index, Index>> directed_edges(const std::vector<Tri>& faces) {
  std::set<std::pair<Index, Index>> edges;
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) edges.insert({f[k], f[(k + 1) % 3]});
  return edges;
}

void check_uses_reversed(const std::vector<Tri>& faces, const std::vector<Index>& loop) {
  const auto edges = directed_edges(faces);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    CHECK(edges.count({loop[(i + 1) % loop.size()], loop[i]}) == 1);
    CHECK(edges.count({loop[i], loop[(i + 1) % loop.size()]}) == 0);
  }
}

std::size_t inconsistent(const std::vector<Tri>& faces, const std::vector<FramedPoint>& points) {
  std::size_t bad = 0;
  for (const Tri& f : faces) bad += !consistent_triangle(points[f[0]], points[f[1]], points[f[2]]);
  return bad;
}

}  // namespace

TEST_CASE("msd refinement band: two rings of different sizes and radii are joined by consistent triangles") {
  std::vector<FramedPoint> points;
  // The patch is the cap around +z (on the left of its border walked east); the template is the
  // rest (on the left of its border walked west), at a smaller radius, as a fitted T_P is.
  const std::vector<Index> inner = ring(points, 13, 0.5, 1.0, true, 0.0);
  const std::vector<Index> outer = ring(points, 21, 0.8, 0.9, false, 0.1);
  const auto band = stitch_band(inner, outer, points);
  REQUIRE(band);
  CHECK(band->size() == inner.size() + outer.size());
  CHECK(inconsistent(*band, points) == 0);
  check_uses_reversed(*band, inner);
  check_uses_reversed(*band, outer);
  // Both borders walked the same way round cannot be joined without folding.
  std::vector<Index> wrong(outer.rbegin(), outer.rend());
  CHECK_FALSE(stitch_band(inner, wrong, points));
}

TEST_CASE("msd refinement cap: a border with nothing to join is closed by n − 2 consistent triangles") {
  std::vector<FramedPoint> points;
  // The patch is everything below the ring (on the left of the ring walked west): the cap covers +z.
  const std::vector<Index> loop = ring(points, 17, 0.6, 1.0, false, 0.0);
  const auto cap = cap_loop(loop, points);
  REQUIRE(cap);
  CHECK(cap->size() == loop.size() - 2);
  CHECK(inconsistent(*cap, points) == 0);
  check_uses_reversed(*cap, loop);
  // Walked the other way the cap would have to face the element: refused.
  CHECK_FALSE(cap_loop(std::vector<Index>(loop.rbegin(), loop.rend()), points));
}
