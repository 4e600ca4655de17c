#pragma once
// Local primitive fitting (paper §5.2, Eqs. 4–7; notes §2.6, §3 S4, §9.1–9.2): the radii ρ of a
// template grow toward a target that is raised 25 times by 10 % of ρ0, smoothed by the template's
// graph Laplacian and kept inside S by the alternating penalty scheme
//   (λ L + w I + ŵ D_Z) ρ = w t + ŵ D_Z ρmax,   Z = {i : ρ_i > ρmax_i},
// one sparse SPD solve per iteration, then the hard clamp ρ ← min(ρ, ρmax). The system is strictly
// diagonally dominant (off-diagonal row sum λ deg_i < diagonal λ deg_i + w), so Jacobi-preconditioned
// conjugate gradients, warm-started at the current ρ, solve it in a few dozen products where a
// Cholesky refactorisation per change of Z cost 70 % of the run (docs/plugins/msd.md).
#include "primitive.hpp"
#include "primitive_template.hpp"
#include "target_mesh.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include <vector>

namespace medax::msd {

/// Every weight of the fitting, with the paper's defaults. The authors' code ([C], notes §9.2)
/// differs: smoothness 0.1 with expansion 2 in the final fit (w/λ = 20), and smoothness 0 while
/// the global optimisation evaluates energies; both are these options set accordingly.
struct FitOptions {
  double smoothness = 1.0;          ///< λ, weight of E_smooth = ρᵀLρ
  double expansion = 10.0;          ///< w, weight of E_exp = ‖ρ − t‖²
  double contact = 1e4;             ///< ŵ, penalty on ρ_i > ρmax_i
  int progressions = 25;            ///< times the target is raised
  double step_fraction = 0.1;       ///< raise per progression, in units of ρ0
  int max_iterations = 15;          ///< inner penalty iterations per progression
  double tolerance = 1e-5;          ///< stop when ‖Δρ‖∞ < tolerance · TargetMesh::scale()
  double solver_tolerance = 1e-12;  ///< relative residual of each conjugate-gradient solve
  /// [C]'s growth rule: direction i's raise shrinks as ρ_i outgrows its smallest neighbour,
  /// step_i = max(0, min(step, 2·step − (ρ_i − min_j∈N(i) ρ_j))). Off in the paper.
  bool neighbour_cap = false;
  TemplateOptions templates;
};

/// The penalty iterations of one primitive.
class RadiusSolver {
 public:
  /// `faces` define the template graph (n vertices); `max_radius` is ρmax; `tolerance` absolute.
  RadiusSolver(const std::vector<Tri>& faces, std::vector<double> max_radius, const FitOptions& options,
               double tolerance);

  /// Inner iterations (≤ options.max_iterations) of Eq. 6 toward `target`, starting from and
  /// updating `radius`; returns the number of solves.
  int solve(const Eigen::VectorXd& target, Eigen::VectorXd& radius);
  /// The whole fit from ρ ≡ initial_radius: the progressions, then the clamp. Adds the number of
  /// solves to `solves` when given.
  std::vector<double> fit(double initial_radius, int* solves = nullptr);

 private:
  /// Writes ŵ D_Z into the diagonal and refreshes the preconditioner when Z changed.
  void set_contact(const std::vector<char>& contact);
  /// t ← ρ + min(ρmax − ρ, step_i) for one progression.
  Eigen::VectorXd progression_target(const Eigen::VectorXd& radius, double step) const;

  FitOptions options_;
  double tolerance_;
  Eigen::VectorXd max_radius_;
  Eigen::SparseMatrix<double> matrix_;       ///< λL + wI + ŵ D_Z, its diagonal rewritten per Z
  std::vector<double*> diagonal_;            ///< pointers into matrix_'s diagonal
  std::vector<double> base_diagonal_;        ///< λ deg_i + w
  std::vector<char> contact_;                ///< Z of the current system
  bool ready_ = false;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver_;
};

/// ρ0 ([C]): distance from S to the vertex, or the mean of the corners' distances.
double initial_radius(const TargetMesh& target, const SkeletonElement& element);

/// Fits one primitive. It fails (fitted = false, `failure` set) when the element is degenerate,
/// touches S, or a direction's ray never leaves S.
Primitive fit_primitive(const TargetMesh& target, const SkeletonElement& element, const FitOptions& options = {});

/// Fits every element in parallel; each primitive is independent, so the result does not
/// depend on the thread count.
std::vector<Primitive> fit_primitives(const TargetMesh& target, const std::vector<SkeletonElement>& elements,
                                      const FitOptions& options = {});

}  // namespace medax::msd
