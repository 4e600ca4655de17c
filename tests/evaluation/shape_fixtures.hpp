#pragma once
// Small fixtures shared by the evaluation stage tests.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <algorithm>
#include <cmath>

namespace medax::test {

/// Largest distance from the exact sphere of radius r (centre 0) to an inscribed icosphere:
/// r minus the smallest distance from the centre to a face plane.
inline double icosphere_sag(const SurfaceMesh& m, double r) {
  double inner = r;
  for (const Tri& f : m.faces) {
    const Vec3 n = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]).normalized();
    inner = std::min(inner, std::abs(n.dot(m.vertices[f[0]])));
  }
  return r - inner;
}

inline MedialComplex one_sphere(double r) {
  MedialComplex mc;
  mc.add_vertex(Vec3::Zero(), r);
  return mc;
}

}  // namespace medax::test
