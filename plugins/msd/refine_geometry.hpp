#pragma once
// Geometry of the element's direction field that the refinement needs (notes §2.8): the direction
// d(x) from the element's closest point b(x), the image of x on the template surface ∂P^ρ0
// (b + ρ0 d, the direction domain), and the exact test that a triangle faces away from a point.
#include "primitive.hpp"

namespace medax::msd::refine {

/// A mesh vertex as the refinement sees it: its position, its base b ∈ P and its image
/// b + ρ0 d on the template surface.
struct FramedPoint {
  Vec3 position;
  Vec3 base;
  Vec3 projected;
};

/// The frame of an S vertex x: b = cp(x; P), d = (x − b)/‖x − b‖; nullopt-like `valid` false
/// when x lies on the element (no direction).
struct Framing {
  FramedPoint point;
  bool valid = false;
};
Framing frame_point(const SkeletonElement& element, double initial_radius, const Vec3& x);

/// Exact (CGAL filtered predicate): the oriented triangle (p, q, r) has `inside` strictly on its
/// inner side, i.e. faces away from it.
bool faces_away(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& inside);

/// The triangle faces away from every corner's base, both in space and in the direction domain
/// (its image on the template surface): no fold-over along the direction field.
bool consistent_triangle(const FramedPoint& a, const FramedPoint& b, const FramedPoint& c);

/// Exact: y lies strictly inside the cone from `apex` over the triangle (p, q, r).
bool in_cone(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& apex, const Vec3& y);

}  // namespace medax::msd::refine
