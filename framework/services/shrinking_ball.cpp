#include <medax/services/shrinking_ball.hpp>

#include <tbb/parallel_for.h>

#include <cmath>

namespace medax::services {

MedialBall shrinking_ball(const PointIndex& surface, const Vec3& p, const Vec3& n, const ShrinkingBallOptions& o) {
  const std::vector<Vec3>& points = surface.points();
  const double min_cos = std::cos(o.denoise_angle_deg * M_PI / 180.0);
  double r = o.initial_radius;
  Vec3 c = p - r * n;
  Vec3 q_prev = p - 2 * r * n;
  Index contact = 0;
  for (int j = 0; j <= o.max_iterations; ++j) {
    const auto [qi, d] = surface.nearest(c);
    const Vec3& q = points[qi];
    if (std::abs(d - r) <= o.tolerance || (q - q_prev).norm() < o.tolerance) break;
    const double den = n.dot(p - q);
    if (den <= 0) break;
    const double r_new = (p - q).squaredNorm() / (2 * den);
    const Vec3 c_new = p - r_new * n;
    if (j > 0) {  // denoising: the ball touches p and q at too small an angle (a noise bump)
      const Vec3 a = (p - c_new).normalized(), b = (q - c_new).normalized();
      if (a.dot(b) > min_cos) break;
    }
    c = c_new;
    r = r_new;
    q_prev = q;
    contact = qi;
  }
  return {c, r, contact};
}

std::vector<MedialBall> shrinking_balls(const PointIndex& surface, const std::vector<Vec3>& points,
                                        const std::vector<Vec3>& normals, const ShrinkingBallOptions& options) {
  std::vector<MedialBall> balls(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(),
                    [&](std::size_t i) { balls[i] = shrinking_ball(surface, points[i], normals[i], options); });
  return balls;
}

}  // namespace medax::services
