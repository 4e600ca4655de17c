#include "update.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <limits>

namespace medax::vmas {

namespace {

struct System {
  double energy = 0;
  Mat4 H = Mat4::Zero();  ///< ½ of the Gauss–Newton Hessian
  Vec4 g = Vec4::Zero();  ///< ½ of the gradient
};

class Objective {
 public:
  Objective(const VmasInput& in, const Index* members, std::size_t count, const UpdateOptions& o)
      : in_(in), members_(members), count_(count) {
    const auto& source = o.rows == SqemRows::Paper ? in.quadrics : in.author_quadrics;
    PackedQuadric sum;
    for (std::size_t i = 0; i < count; ++i) {
      const PackedQuadric& q = source[members[i]];
      for (int k = 0; k < 14; ++k) sum.k[k] += q.k[k];
      sum.c += q.c;
    }
    Q_ = sum.unpack();
    weight_ = o.rows == SqemRows::Paper ? o.lambda : o.lambda * o.lambda;
  }

  /// Energy, and optionally the Gauss–Newton system, at s.
  System at(const Vec4& s, bool with_system) const {
    System sys;
    const Vec3 q = s.head<3>();
    const double r = s[3];
    double e = 0;
    Mat4 JtJ = Mat4::Zero();
    Vec4 Jtr = Vec4::Zero();
    for (std::size_t i = 0; i < count_; ++i) {
      const Index v = members_[i];
      const double a = in_.areas[v];
      const Vec3 delta = in_.points[v] - q;
      const double l = delta.norm();
      const double rho = l - r;
      e += a * rho * rho;
      if (!with_system || l < 1e-12 * in_.scale) continue;  // J undefined at the centre
      const Vec4 J(-delta.x() / l, -delta.y() / l, -delta.z() / l, -1.0);
      JtJ.noalias() += a * J * J.transpose();
      Jtr += (a * rho) * J;
    }
    sys.energy = Q_(s) + weight_ * e;
    if (with_system) {
      sys.H = 0.5 * Q_.A + weight_ * JtJ;
      sys.g = 0.5 * (Q_.A * s - Q_.b) + weight_ * Jtr;
    }
    return sys;
  }

 private:
  const VmasInput& in_;
  const Index* members_;
  std::size_t count_;
  Quadric Q_;
  double weight_ = 0;
};

}  // namespace

double update_energy(const VmasInput& in, const Index* members, std::size_t count, const Sphere& s,
                     const UpdateOptions& options) {
  return Objective(in, members, count, options).at(s.s(), false).energy;
}

namespace {

/// Levenberg-guarded Gauss–Newton: a step that raises the energy or makes r ≤ 0 is retried with
/// more damping, so the energy never increases.
UpdateResult guarded_steps(const Objective& f, const Sphere& start, const UpdateOptions& options) {
  Vec4 s = start.s();
  System cur = f.at(s, true);
  UpdateResult result;
  result.energy_before = cur.energy;
  double mu = 0;
  for (int it = 0; it < options.max_iterations; ++it) {
    ++result.iterations;
    Mat4 H = cur.H;
    if (mu > 0) H.diagonal() += mu * cur.H.diagonal().cwiseMax(1e-300);
    const Eigen::LDLT<Mat4> ldlt(H);
    Vec4 delta = Vec4::Constant(std::numeric_limits<double>::quiet_NaN());
    if (ldlt.info() == Eigen::Success) delta = ldlt.solve(-cur.g);
    const Vec4 trial = s + delta;
    bool accepted = false;
    if (delta.allFinite() && trial[3] > 0) {
      const System next = f.at(trial, true);
      if (std::isfinite(next.energy) && next.energy <= cur.energy) {
        s = trial;
        cur = next;
        accepted = true;
        mu = mu > 0 ? mu * 0.1 : 0.0;
        if (mu < 1e-12) mu = 0;
      }
    }
    if (accepted) {
      if (delta.norm() < options.tolerance) {
        result.converged = true;
        break;
      }
      continue;
    }
    // Rejected: damp (Levenberg) and retry from the same point; give up when the step vanishes.
    mu = mu > 0 ? mu * 10 : 1e-4;
    if (mu > 1e8 || (delta.allFinite() && delta.norm() < options.tolerance)) {
      result.converged = true;
      break;
    }
  }
  result.sphere = Sphere::from(s);
  result.energy_after = cur.energy;
  return result;
}

/// Plain Gauss–Newton, as the authors' code: s += Δ every iteration, stop when |Δ| < tolerance.
/// Only a singular system (or a non-finite step) stops it early, keeping the last sphere.
UpdateResult raw_steps(const Objective& f, const Sphere& start, const UpdateOptions& options) {
  Vec4 s = start.s();
  System cur = f.at(s, true);
  UpdateResult result;
  result.energy_before = cur.energy;
  for (int it = 0; it < options.max_iterations; ++it) {
    ++result.iterations;
    const Eigen::LDLT<Mat4> ldlt(cur.H);
    const Vec4 delta = ldlt.solve(-cur.g);
    if (ldlt.info() != Eigen::Success || !delta.allFinite()) {
      result.converged = true;  // nothing more this solve can do
      break;
    }
    s += delta;
    cur = f.at(s, true);
    if (delta.norm() < options.tolerance) {
      result.converged = true;
      break;
    }
  }
  result.sphere = Sphere::from(s);
  result.energy_after = cur.energy;
  return result;
}

}  // namespace

UpdateResult update_sphere(const VmasInput& in, const Index* members, std::size_t count, const Sphere& start,
                           const UpdateOptions& options) {
  const Objective f(in, members, count, options);
  return options.steps == GaussNewtonSteps::Raw ? raw_steps(f, start, options) : guarded_steps(f, start, options);
}

}  // namespace medax::vmas
