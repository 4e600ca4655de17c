#pragma once
// Analytic shapes with known medial axes, for testing any stage (ours or a third party's) the
// same way. Each generator returns a closed, outward-oriented triangle mesh; each `*_axis`
// function is the exact distance from a point to the shape's inner medial axis.
#include <medax/surface.hpp>

namespace medax::testing {

/// Icosphere of radius r centred at the origin; `subdivisions` 0 gives 20 faces, each level ×4.
SurfaceMesh make_sphere(double r, int subdivisions);
/// Ellipsoid with semi-axes a, b, c along x, y, z (a scaled icosphere).
SurfaceMesh make_ellipsoid(double a, double b, double c, int subdivisions);
/// Capsule: the points within `radius` of the segment z ∈ [-half_length, half_length].
/// `segments` around the axis; hemispheres and cylinder are sampled at a matching density.
SurfaceMesh make_capsule(double radius, double half_length, int segments);
/// Closed cylinder of radius r, z ∈ [-half_height, half_height].
SurfaceMesh make_cylinder(double r, double half_height, int segments);
/// Torus around the z-axis: core circle radius R, tube radius r; nu × nv quads split in two.
SurfaceMesh make_torus(double R, double r, int nu, int nv);
/// Box [-ax, ax] × [-ay, ay] × [-az, az], each face an n × n grid.
SurfaceMesh make_box(double ax, double ay, double az, int n);

/// Exact distances to inner medial axes.
double sphere_axis_distance(const Vec3& p);                        ///< the centre
double capsule_axis_distance(const Vec3& p, double half_length);   ///< the core segment
double torus_axis_distance(const Vec3& p, double R);               ///< the core circle
/// Ellipsoid a > b > c: the planar region z = 0, x²/A² + y²/B² ≤ 1, A = (a²−c²)/a, B = (b²−c²)/b.
double ellipsoid_axis_distance(const Vec3& p, double a, double b, double c);

}  // namespace medax::testing
