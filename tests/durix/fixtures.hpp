#pragma once
// Shared helpers of the durix tests: fixture meshes, conversion, the invariant checks of
// notes §5 applied to one run.
#include "delaunay_mesh.hpp"
#include "durix.hpp"

#include <medax/surface.hpp>

#include <array>
#include <string>
#include <vector>

namespace medax::durix::test {

/// Fixture meshes by name: sphere (icosphere, radially jittered), ellipsoid, box, torus,
/// capsule; already converted to Delaunay meshes.
SurfaceMesh fixture(const std::string& name);
/// An ellipsoid (a, b, c) = (1.2, 1, 0.8) with a smooth bump of `height` at its top (+z).
SurfaceMesh bumped_ellipsoid(double height);
/// The union of unit cubes at integer `cells` (face-adjacent only: no two cells may share just an
/// edge or a vertex), each cube face split into n × n squares of two triangles: a CAD-like solid
/// with sharp convex and concave creases. Not converted.
SurfaceMesh cube_union(const std::vector<std::array<int, 3>>& cells, int n);
/// Runs the conversion and requires it to verify.
SurfaceMesh to_delaunay(const SurfaceMesh& mesh);

/// Checks every invariant of notes §5 on a result (Catch2 CHECKs inside).
void check_invariants(const SurfaceMesh& input, const DurixResult& result, double epsilon);

}  // namespace medax::durix::test
