#include "refine_geometry.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>

namespace medax::msd::refine {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

bool faces_away_all(const Vec3& p, const Vec3& q, const Vec3& r, const FramedPoint& a, const FramedPoint& b,
                    const FramedPoint& c) {
  return faces_away(p, q, r, a.base) && faces_away(p, q, r, b.base) && faces_away(p, q, r, c.base);
}

}  // namespace


Framing frame_point(const SkeletonElement& element, double initial_radius, const Vec3& x) {
  Framing framing;
  const Vec3 base = element.closest_point(x);
  const double length = (x - base).norm();
  if (!(length > 0)) return framing;
  framing.point = {x, base, base + initial_radius * (x - base) / length};
  framing.valid = true;
  return framing;
}

bool faces_away(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& inside) {
  return CGAL::orientation(point(p), point(q), point(r), point(inside)) == CGAL::NEGATIVE;
}

bool in_cone(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& apex, const Vec3& y) {
  const auto same_side = [&](const Vec3& a, const Vec3& b, const Vec3& opposite) {
    const auto side = CGAL::orientation(point(a), point(b), point(apex), point(y));
    return side != CGAL::COPLANAR && side == CGAL::orientation(point(a), point(b), point(apex), point(opposite));
  };
  return same_side(p, q, r) && same_side(q, r, p) && same_side(r, p, q);
}

bool consistent_triangle(const FramedPoint& a, const FramedPoint& b, const FramedPoint& c) {
  return faces_away_all(a.position, b.position, c.position, a, b, c) &&
         faces_away_all(a.projected, b.projected, c.projected, a, b, c);
}

}  // namespace medax::msd::refine
