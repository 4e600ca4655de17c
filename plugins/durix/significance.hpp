#pragma once
// The ε-significance test of Durix et al. (paper §3.5, notes §2.5): a surface region beyond a
// singular path is insignificant when every one of its vertices lies within ε of one of the
// path's medial balls, i.e. ‖v − c‖ < r + ε for some ball (c, r) of the path.
//
// The propagation asks a RegionOracle; the `durix_epsilon` stage makes one. Another stage can
// make a different oracle (a different tolerance per region, a different distance) without
// touching the propagation.
#include <medax/geometry.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace medax::durix {

struct Ball {
  Vec3 centre;
  double radius = 0;
};

class RegionOracle {
 public:
  virtual ~RegionOracle() = default;
  /// The absolute tolerance (in the shape's units); 0 disables every removal.
  virtual double epsilon() const = 0;
  /// True when p is covered by the balls inflated by the tolerance. `hint` is the index of the
  /// ball that covered the previous query of the same region (a speed-up; any value is valid).
  virtual bool covered(const Vec3& p, const std::vector<Ball>& balls, std::size_t& hint) const = 0;
};

/// The paper's test: ‖p − c‖ < r + ε for some ball.
class EpsilonOracle : public RegionOracle {
 public:
  explicit EpsilonOracle(double epsilon) : epsilon_(epsilon) {}
  double epsilon() const override { return epsilon_; }
  bool covered(const Vec3& p, const std::vector<Ball>& balls, std::size_t& hint) const override {
    if (epsilon_ <= 0 || balls.empty()) return false;
    const std::size_t n = balls.size();
    if (hint >= n) hint = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (hint + i) % n;
      const double reach = balls[j].radius + epsilon_;
      if ((p - balls[j].centre).squaredNorm() < reach * reach) {
        hint = j;
        return true;
      }
    }
    return false;
  }

 private:
  double epsilon_;
};

/// min over balls of (‖p − c‖ − r): how far p is outside the union of the balls.
inline double ball_excess(const Vec3& p, const std::vector<Ball>& balls) {
  double best = std::numeric_limits<double>::infinity();
  for (const Ball& b : balls) best = std::min(best, (p - b.centre).norm() - b.radius);
  return best;
}

}  // namespace medax::durix
