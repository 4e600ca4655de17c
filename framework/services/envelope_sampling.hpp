#pragma once
// Internal to the envelope service: points on the envelope's boundary ∂E, one per edge of a
// regular grid that crosses it (Envelope::sample_boundary in medax/services/envelope.hpp).
#include "envelope_bvh.hpp"

#include <medax/services/envelope.hpp>

#include <functional>

namespace medax::services::envelope_detail {

/// The boundary points of the envelope whose primitives `bvh` holds, at grid spacing `step`.
/// Throws std::invalid_argument when the step is not positive or too small for the envelope.
EnvelopeSamples sample_boundary(const EnvelopeBvh& bvh, double step, const std::function<void(double)>& progress);

}  // namespace medax::services::envelope_detail
