#pragma once
// Internal: conversions between medax::SurfaceMesh and CGAL types (never in public headers).
#include <medax/surface.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace medax::services::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;

inline Point to_point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }
inline Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

/// Builds a CGAL Surface_mesh; vertex and face indices are kept (vertex i is index i).
/// Faces that cannot be added (non-manifold) are skipped; returns how many were skipped.
std::size_t to_cgal(const SurfaceMesh& mesh, CgalMesh& out);

}  // namespace medax::services::detail
