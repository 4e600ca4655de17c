#include "correction.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/services/shrinking_ball.hpp>

#include <algorithm>
#include <cmath>

namespace medax::qmat {

namespace {

Vec3 unit_face_normal(const SurfaceMesh& mesh, Index f) {
  const Tri& t = mesh.faces[f];
  const Vec3& a = mesh.vertices[t[0]];
  return (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
}

}  // namespace

CorrectionReport shrinking_ball_correction(MedialComplex& medial, const SurfaceMesh& surface) {
  const services::SurfaceDistance closest(surface);
  const services::PointIndex vertices(surface.vertices);
  const double diagonal = bbox_diagonal(surface.vertices);
  services::ShrinkingBallOptions options;
  options.initial_radius = diagonal;  // the ball only shrinks: start from the whole shape
  options.tolerance = 1e-5 * diagonal;
  CorrectionReport report;
  for (std::size_t v = 0; v < medial.num_vertices(); ++v) {
    const Vec3 centre = medial.centres[v];
    const services::ClosestPoint cp = closest.closest(centre);
    const Vec3 face_normal = unit_face_normal(surface, cp.face);
    // The shrinking ball's normal points out of the ball at p: from q* to p, oriented outward
    // by the face so the ball grows inward even from a centre outside the shape (as VMAS's code).
    Vec3 n = cp.point - centre;
    n = n.norm() > 1e-12 * diagonal ? Vec3(n.normalized()) : face_normal;
    if (n.dot(face_normal) <= 0) n = -n;
    const services::MedialBall ball = services::shrinking_ball(vertices, cp.point, n, options);
    if (!(ball.radius > 0 && ball.radius < 0.999 * options.initial_radius && ball.centre.allFinite())) {
      ++report.kept;
      continue;
    }
    report.max_shift =
        std::max(report.max_shift, (ball.centre - centre).norm() + std::abs(ball.radius - medial.radii[v]));
    medial.centres[v] = ball.centre;
    medial.radii[v] = ball.radius;
    ++report.corrected;
  }
  return report;
}

}  // namespace medax::qmat
