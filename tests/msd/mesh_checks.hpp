#pragma once
// Checks on closed triangle meshes shared by the msd tests (templates, fitted primitives, Ŝ).
#include <medax/geometry.hpp>
#include <medax/services/closest_point.hpp>
#include <medax/surface.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace medax::msd::checks {

/// Vertices whose faces do not form one fan (a pinch where two sheets touch at a point).
inline std::size_t pinched_vertices(const std::vector<Tri>& faces, std::size_t vertices) {
  std::vector<std::map<Index, Index>> next(vertices);  // around vertex a: face (a, b, c) links b → c
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) next[f[k]][f[(k + 1) % 3]] = f[(k + 2) % 3];
  std::size_t pinched = 0;
  for (const auto& fan : next) {
    if (fan.empty()) continue;
    std::size_t steps = 0;
    Index at = fan.begin()->first;
    do {
      const auto it = fan.find(at);
      if (it == fan.end()) break;
      at = it->second;
      ++steps;
    } while (at != fan.begin()->first && steps <= fan.size());
    if (steps != fan.size()) ++pinched;
  }
  return pinched;
}

/// Closed, 2-manifold (every edge in two faces of opposite direction, every vertex one fan),
/// consistently oriented, with Euler characteristic `euler` (2: sphere topology).
inline void check_closed_manifold(const std::vector<Tri>& faces, std::size_t vertices, long euler = 2) {
  std::map<std::pair<Index, Index>, int> directed;
  for (const Tri& f : faces) {
    REQUIRE(f[0] != f[1]);
    REQUIRE(f[1] != f[2]);
    REQUIRE(f[0] != f[2]);
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  std::size_t bad = 0;
  for (const auto& [edge, count] : directed)
    if (count != 1 || directed.count({edge.second, edge.first}) == 0) ++bad;
  CHECK(bad == 0);
  CHECK(pinched_vertices(faces, vertices) == 0);
  const std::size_t edges = directed.size() / 2;
  CHECK(static_cast<long>(vertices) - static_cast<long>(edges) + static_cast<long>(faces.size()) == euler);
}

/// Generalized winding number of p with respect to a closed triangle mesh.
inline double winding(const std::vector<Vec3>& v, const std::vector<Tri>& faces, const Vec3& p) {
  double total = 0;
  for (const Tri& f : faces) {
    const Vec3 a = v[f[0]] - p, b = v[f[1]] - p, c = v[f[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    total += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return total / (4 * M_PI);
}

/// Mean distance from `points` to `mesh`.
inline double mean_distance(const std::vector<Vec3>& points, const SurfaceMesh& mesh) {
  const std::vector<double> d = services::SurfaceDistance(mesh).distances(points);
  double sum = 0;
  for (double x : d) sum += x;
  return sum / static_cast<double>(d.size());
}

/// MSD's ε̄ = max(ε̄¹, ε̄²) over vertices: S's to Ŝ and Ŝ's to S.
inline double two_sided_error(const SurfaceMesh& surface, const SurfaceMesh& rebuilt) {
  return std::max(mean_distance(surface.vertices, rebuilt), mean_distance(rebuilt.vertices, surface));
}

}  // namespace medax::msd::checks
