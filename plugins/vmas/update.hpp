#pragma once
// The sphere update (notes §2.4, eqs. 9–11): m* = argmin_s Σ_{v∈C} Q_v(s) + λ Σ_{v∈C} A(v) d_v(s)²,
// by Gauss–Newton from the current sphere. The SQEM part is quadratic (its Gauss–Newton step is
// exact): the cluster's quadric is summed once, and each iteration makes one pass over the
// cluster for the Euclidean part, accumulating the 4×4 system directly.
//
// Steps (GaussNewtonSteps): `Guarded` (notes [R]) accepts a step only if it does not increase
// the energy and keeps r > 0, otherwise raises Levenberg damping μ·diag(H) and retries, so the
// energy of a cluster never increases across an update; `Raw` takes the plain Gauss–Newton step
// every time, as both of the authors' implementations do.
#include "input.hpp"

namespace medax::vmas {

/// Which energy the update minimises (notes §2.4, "reproduction caveats").
enum class SqemRows {
  Paper,       ///< eqs. 9–11: Σ_v Q_v with Q_v a sum of plane quadrics; Euclidean weight λ
  AuthorCode,  ///< the authors' code: one summed residual row per vertex, (Σ_t √w_t d_t)²;
               ///< Euclidean rows scaled by λ, so the effective weight is λ²
};

/// How the Gauss–Newton iteration moves (notes §2.4).
enum class GaussNewtonSteps {
  Guarded,  ///< energy test + Levenberg damping, r > 0 (ours)
  Raw,      ///< s += Δ with Δ = −H⁻¹g, no test (the authors' CGoGN code and CGAL port)
};

struct UpdateOptions {
  double lambda = 0.2;  ///< λ_update
  SqemRows rows = SqemRows::Paper;
  GaussNewtonSteps steps = GaussNewtonSteps::Guarded;
  int max_iterations = 10;
  double tolerance = 1e-6;  ///< stop when |Δs| is below this (absolute length)
};

struct UpdateResult {
  Sphere sphere;
  double energy_before = 0, energy_after = 0;  ///< of the minimised objective
  int iterations = 0;
  bool converged = false;  ///< stopped before max_iterations (a short step, or no descent left)
};

/// Minimises the update energy of the cluster `members` (ascending) from `start`.
UpdateResult update_sphere(const VmasInput& in, const Index* members, std::size_t count, const Sphere& start,
                           const UpdateOptions& options);

/// The update energy itself (for tests).
double update_energy(const VmasInput& in, const Index* members, std::size_t count, const Sphere& s,
                     const UpdateOptions& options);

}  // namespace medax::vmas
