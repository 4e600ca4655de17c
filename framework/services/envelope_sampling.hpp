#pragma once
// Internal to the envelope service: points on the envelope's boundary ∂E, one per edge of a
// regular grid that crosses it (Envelope::sample_boundary in medax/services/envelope.hpp).
#include "envelope_bvh.hpp"

#include <medax/services/envelope.hpp>

#include <functional>

namespace medax::services::envelope_detail {

/// Calls a CancelCheck at every kPollEvery-th item of a (parallel) loop: each item of these loops
/// is a BVH query (microseconds), so a stop is seen within about a millisecond per thread, and
/// the check (an atomic read) costs nothing measurable.
class CancelPoll {
 public:
  static constexpr std::size_t kPollEvery = 256;
  explicit CancelPoll(const CancelCheck& check) : check_(check) {}
  void at(std::size_t item) const {
    if (item % kPollEvery == 0) now();
  }
  void now() const {
    if (check_) check_();
  }

 private:
  const CancelCheck& check_;
};

/// The boundary points of the envelope whose primitives `bvh` holds, at grid spacing `step`.
/// Throws std::invalid_argument when the step is not positive or too small for the envelope.
EnvelopeSamples sample_boundary(const EnvelopeBvh& bvh, double step, const std::function<void(double)>& progress,
                                const CancelPoll& poll);

/// Boundary points on the grid of sample_boundary(step), from the grid edges whose ends both lie
/// in a shell inner[i] ≤ |z − centres[i]| ≤ outer[i]: a local, finer sampling (every point exactly
/// on ∂E, the point sample_boundary gives that edge). seeds[i] (a primitive in BVH order, e.g.
/// the deepest at centres[i]) starts the searches around centres[i].
std::vector<Vec3> sample_boundary_near(const EnvelopeBvh& bvh, double step, const std::vector<Vec3>& centres,
                                       const std::vector<double>& inner, const std::vector<double>& outer,
                                       const std::vector<std::int64_t>& seeds, const CancelPoll& poll);

}  // namespace medax::services::envelope_detail
