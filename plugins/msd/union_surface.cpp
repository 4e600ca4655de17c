#include "union_surface.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/inside.hpp>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <stdexcept>

namespace medax::msd {
namespace {

using Corners = std::array<Vec3, 3>;

/// Precision of the cuts (bisection, merging) in units of the longest box side of all solids.
constexpr double kPrecision = 1e-9;
/// Points this many precisions apart are one point when a triangle is cut.
constexpr double kMergePrecisions = 4;
/// Halvings of a triangle whose corners are inside a solid but whose centroid is not.
constexpr int kSplits = 2;
constexpr Index kUnused = static_cast<Index>(-1);

/// One solid and its two queries (CGAL AABB trees in the services).
struct Solid {
  explicit Solid(const SurfaceMesh& mesh) : side(mesh), surface(mesh) {
    for (const Vec3& v : mesh.vertices) box.extend(v);
  }
  services::InsideTest side;
  services::SurfaceDistance surface;
  Eigen::AlignedBox3d box;
};

/// Where a point is with respect to a solid: outside, on its surface (within the tolerance) or
/// inside (deeper than the tolerance).
enum class Side : char { Out, On, In };
using Sides = std::array<Side, 3>;

bool any(const Sides& sides, Side side) { return std::find(sides.begin(), sides.end(), side) != sides.end(); }

Vec3 centroid(const Corners& t) { return (t[0] + t[1] + t[2]) / 3; }

/// The four triangles of `t` split at its edges' midpoints, oriented as `t`.
std::array<Corners, 4> quarters(const Corners& t) {
  const Vec3 a = 0.5 * (t[0] + t[1]), b = 0.5 * (t[1] + t[2]), c = 0.5 * (t[2] + t[0]);
  return {Corners{t[0], a, c}, Corners{a, t[1], b}, Corners{c, b, t[2]}, Corners{a, b, c}};
}

enum class Verdict { Keep, Drop, Cut, Split };

/// Cuts triangles of other solids against one solid.
class Cutter {
 public:
  Cutter(const Solid& solid, double tolerance, double precision)
      : solid_(solid), tolerance_(tolerance), precision_(precision) {}

  Side side(const Vec3& x) const {
    if (solid_.box.exteriorDistance(x) > tolerance_) return Side::Out;
    if (solid_.surface.distance(x) <= tolerance_) return Side::On;
    return solid_.side.inside(x) ? Side::In : Side::Out;
  }
  /// What becomes of triangle `t` against the solid, from where its corners are (`sides`) and,
  /// when no corner is outside, its centroid.
  Verdict verdict(const Corners& t, const Sides& sides) const {
    const bool in = any(sides, Side::In), out = any(sides, Side::Out);
    if (in && out) return Verdict::Cut;
    if (out) return Verdict::Keep;  // a solid poking through its interior is missed
    const Side centre = side(centroid(t));
    if (centre == Side::In) return Verdict::Drop;
    // Corners in and the centre outside: t leaves the solid between its corners. Corners in and
    // the centre on the surface: inside as far as the tolerance tells. All on and the centre not
    // in: a face the two share.
    if (in) return centre == Side::Out ? Verdict::Split : Verdict::Drop;
    return Verdict::Keep;
  }

  /// Appends the part of triangle `t` outside the solid as triangles; `splits` more halvings are
  /// allowed where the corners do not decide (the last level keeps what it cannot decide).
  void clip(const Corners& t, std::vector<Corners>& kept, int splits = kSplits) const {
    const Sides sides{side(t[0]), side(t[1]), side(t[2])};
    switch (verdict(t, sides)) {
      case Verdict::Keep:
        return kept.push_back(t);
      case Verdict::Drop:
        return;
      case Verdict::Split:
        if (splits == 0) return kept.push_back(t);
        for (const Corners& quarter : quarters(t)) clip(quarter, kept, splits - 1);
        return;
      case Verdict::Cut:
        break;
    }
    std::vector<Vec3> polygon;  // t's outside part, in t's cyclic order: at most 4 corners, convex
    const auto add = [&polygon](const Vec3& x) {
      if (polygon.empty() || polygon.back() != x) polygon.push_back(x);
    };
    for (int k = 0; k < 3; ++k) {
      const int next = (k + 1) % 3;
      const bool in = sides[k] == Side::In, next_in = sides[next] == Side::In;
      if (!in) add(t[k]);
      if (in != next_in) add(in ? entry(t[next], t[k]) : entry(t[k], t[next]));
    }
    if (polygon.size() > 1 && polygon.front() == polygon.back()) polygon.pop_back();
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) kept.push_back({polygon[0], polygon[i], polygon[i + 1]});
  }

 private:
  /// Where the segment from `out` (not inside) to `in` (inside) enters the solid, on the outside
  /// side, to within the precision (bisection: the solid's surface need not be met once). An entry
  /// within a few precisions of `out` is `out` itself, so a triangle touching the solid along an
  /// edge or at a corner leaves no sliver.
  Vec3 entry(const Vec3& out, Vec3 in) const {
    Vec3 last_out = out;
    while ((in - last_out).norm() > precision_) {
      const Vec3 mid = 0.5 * (last_out + in);
      (side(mid) == Side::In ? in : last_out) = mid;
    }
    return (last_out - out).norm() <= kMergePrecisions * precision_ ? out : last_out;
  }

  const Solid& solid_;
  double tolerance_, precision_;
};

/// The triangles of one solid's `mesh` outside the others (`overlapping`: those whose boxes meet its box).
std::vector<Corners> outside_part(const SurfaceMesh& mesh, const std::vector<Cutter>& overlapping,
                                  std::atomic<std::size_t>& cut) {
  // sides[j][v]: where vertex v is with respect to overlapping solid j.
  std::vector<std::vector<Side>> sides(overlapping.size(), std::vector<Side>(mesh.vertices.size(), Side::Out));
  for (std::size_t j = 0; j < overlapping.size(); ++j)
    tbb::parallel_for(std::size_t{0}, mesh.vertices.size(),
                      [&](std::size_t v) { sides[j][v] = overlapping[j].side(mesh.vertices[v]); });
  std::vector<Corners> kept;
  for (const Tri& f : mesh.faces) {
    const Corners t{mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]};
    std::vector<const Cutter*> cutting;
    bool covered = false;
    for (std::size_t j = 0; j < overlapping.size() && !covered; ++j) {
      const Verdict v = overlapping[j].verdict(t, {sides[j][f[0]], sides[j][f[1]], sides[j][f[2]]});
      covered = v == Verdict::Drop;
      if (v == Verdict::Cut || v == Verdict::Split) cutting.push_back(&overlapping[j]);
    }
    if (covered) continue;
    std::vector<Corners> pieces{t};
    if (!cutting.empty()) ++cut;
    for (const Cutter* solid : cutting) {
      std::vector<Corners> clipped;
      for (const Corners& piece : pieces) solid->clip(piece, clipped);
      pieces.swap(clipped);
    }
    kept.insert(kept.end(), pieces.begin(), pieces.end());
  }
  return kept;
}

/// Corner triple rotated so that the smallest index comes first (keeps the orientation).
std::array<Index, 3> canonical(Index a, Index b, Index c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

/// One mesh of all kept triangles: equal points merged, degenerate triangles (area below
/// `min_area`) and repeated ones dropped, and both copies of a triangle present in the two
/// orientations dropped (an interface between two solids, inside the union). Only used points stay.
SurfaceMesh weld(const std::vector<std::vector<Corners>>& parts, double min_area) {
  std::vector<Vec3> points;
  std::map<std::array<double, 3>, Index> index;
  const auto point = [&](const Vec3& x) {
    const auto [it, added] = index.emplace(std::array<double, 3>{x.x(), x.y(), x.z()}, points.size());
    if (added) points.push_back(x);
    return it->second;
  };
  std::vector<std::array<Index, 3>> faces;
  for (const auto& part : parts)
    for (const Corners& t : part) {
      if ((t[1] - t[0]).cross(t[2] - t[0]).norm() <= 2 * min_area) continue;
      const Index a = point(t[0]), b = point(t[1]), c = point(t[2]);
      if (a != b && b != c && a != c) faces.push_back(canonical(a, b, c));
    }
  std::map<std::array<Index, 3>, int> copies;
  for (const auto& f : faces) ++copies[f];
  SurfaceMesh mesh;
  std::vector<Index> renumber(points.size(), kUnused);
  for (const auto& f : faces) {
    int& count = copies[f];
    if (count == 0 || copies.count(canonical(f[0], f[2], f[1]))) continue;  // emitted, or an interface
    count = 0;
    Tri face;
    for (int k = 0; k < 3; ++k) {
      if (renumber[f[k]] == kUnused) {
        renumber[f[k]] = static_cast<Index>(mesh.vertices.size());
        mesh.vertices.push_back(points[f[k]]);
      }
      face[k] = renumber[f[k]];
    }
    mesh.faces.push_back(face);
  }
  return mesh;
}

double longest_side(const std::vector<SurfaceMesh>& solids) {
  Eigen::AlignedBox3d box;
  for (const SurfaceMesh& s : solids)
    for (const Vec3& v : s.vertices) box.extend(v);
  return box.isEmpty() ? 0.0 : box.sizes().maxCoeff();
}

}  // namespace

ReconstructedSurface reconstruct_union(const std::vector<SurfaceMesh>& solids, const Similarity& to_input,
                                       const UnionOptions& options) {
  if (std::all_of(solids.begin(), solids.end(), [](const SurfaceMesh& s) { return s.faces.empty(); }))
    throw std::invalid_argument("no primitive surface to build Ŝ from (every primitive failed or was left out)");
  const double scale = longest_side(solids);
  const double tolerance = options.tolerance * scale, precision = kPrecision * scale;
  std::vector<std::unique_ptr<Solid>> built(solids.size());
  tbb::parallel_for(std::size_t{0}, solids.size(), [&](std::size_t k) {
    if (!solids[k].faces.empty()) built[k] = std::make_unique<Solid>(solids[k]);
  });
  std::vector<std::vector<Corners>> parts(solids.size());
  std::atomic<std::size_t> cut{0};
  tbb::parallel_for(std::size_t{0}, solids.size(), [&](std::size_t p) {
    if (!built[p]) return;
    std::vector<Cutter> overlapping;
    for (std::size_t q = 0; q < solids.size(); ++q)
      if (q != p && built[q] && built[q]->box.intersects(built[p]->box))
        overlapping.emplace_back(*built[q], tolerance, precision);
    parts[p] = outside_part(solids[p], overlapping, cut);
  });
  ReconstructedSurface result;
  result.surface = weld(parts, precision * precision);
  result.to_input = to_input;
  const auto used = std::count_if(built.begin(), built.end(), [](const auto& s) { return s != nullptr; });
  result.method = fmt::format("union of {} primitive surfaces without a grid: triangles outside the other primitives, "
                              "{} cut where they enter one (tolerance {:.2g}); open along the cuts",
                              used, cut.load(), options.tolerance);
  return result;
}

}  // namespace medax::msd
