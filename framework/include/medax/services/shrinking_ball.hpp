#pragma once
// Shrinking-ball medial spheres (Ma, Bae, Choi, Kim 2012), constants as in
// docs/notes/huang2024_vmas.md §2.7.
#include <medax/services/kdtree.hpp>

namespace medax::services {

struct ShrinkingBallOptions {
  double initial_radius = 1.0;  ///< r0; the ball only shrinks, so use ≥ the bbox diagonal
  int max_iterations = 30;
  double tolerance = 1e-5;          ///< stop when |d − r| or the move of q is below this
  double denoise_angle_deg = 20.0;  ///< stop when the ball's contact angle gets this small
};

struct MedialBall {
  Vec3 centre;
  double radius = 0;
  Index contact = 0;  ///< the second contact point (index into the k-d tree's points)
};

/// The maximal inner ball touching `p` (outward unit normal `n`) and one other point of the
/// tree. For outer balls pass −n.
MedialBall shrinking_ball(const PointIndex& surface_points, const Vec3& p, const Vec3& n,
                          const ShrinkingBallOptions& options = {});

/// One ball per point (points and normals of the same length), in parallel.
std::vector<MedialBall> shrinking_balls(const PointIndex& surface_points, const std::vector<Vec3>& points,
                                        const std::vector<Vec3>& normals, const ShrinkingBallOptions& options = {});

}  // namespace medax::services
