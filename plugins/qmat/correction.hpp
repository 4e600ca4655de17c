#pragma once
// The shrinking-ball correction that the VMAS paper applies to every baseline's output (VMAS §3.3
// "Sphere projection", §4): each sphere (q*, r*) is replaced by the shrinking ball started at the
// surface point p closest to q*, in the direction d = (q* − p)/‖q* − p‖.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

namespace medax::qmat {

struct CorrectionReport {
  std::size_t corrected = 0;  ///< spheres replaced by their shrinking ball
  std::size_t kept = 0;       ///< spheres kept (the ball found no second contact)
  double max_shift = 0;       ///< largest ‖q̂ − q*‖ + |r̂ − r*|
};

/// Replaces every vertex's centre and radius (edges, faces and columns unchanged).
CorrectionReport shrinking_ball_correction(MedialComplex& medial, const SurfaceMesh& surface);

}  // namespace medax::qmat
