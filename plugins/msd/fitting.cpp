#include "fitting.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace medax::msd {
namespace {

/// Graph Laplacian λL plus w on the diagonal, with every diagonal entry stored.
Eigen::SparseMatrix<double> system_matrix(const std::vector<Tri>& faces, std::size_t n, double smoothness,
                                          double expansion) {
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> degree(n, 0.0);
  for (const Segment& e : template_edges(faces)) {
    entries.emplace_back(e[0], e[1], -smoothness);
    entries.emplace_back(e[1], e[0], -smoothness);
    degree[e[0]] += 1;
    degree[e[1]] += 1;
  }
  for (std::size_t i = 0; i < n; ++i) entries.emplace_back(i, i, smoothness * degree[i] + expansion);
  Eigen::SparseMatrix<double> matrix(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

std::vector<double> max_radii(const TargetMesh& target, const PrimitiveTemplate& shape, std::string& failure) {
  std::vector<double> result(shape.size());
  std::size_t missed = 0, touching = 0;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    const auto hit = target.first_exit(shape.base[i], shape.direction[i]);
    if (!hit) ++missed;
    else if (*hit <= 0) ++touching;
    result[i] = hit.value_or(0.0);
  }
  if (missed > 0)
    failure = fmt::format("{} of {} directions never leave the shape (is the element outside S?)", missed, shape.size());
  else if (touching > 0)
    failure = fmt::format("the element touches the surface ({} of {} directions have no room)", touching, shape.size());
  return result;
}

}  // namespace

RadiusSolver::RadiusSolver(const std::vector<Tri>& faces, std::vector<double> max_radius, const FitOptions& options,
                           double tolerance)
    : options_(options), tolerance_(tolerance), max_radius_(Eigen::Map<const Eigen::VectorXd>(max_radius.data(), max_radius.size())) {
  const std::size_t n = max_radius.size();
  matrix_ = system_matrix(faces, n, options.smoothness, options.expansion);
  diagonal_.resize(n);
  base_diagonal_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    diagonal_[i] = &matrix_.coeffRef(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
    base_diagonal_[i] = *diagonal_[i];
  }
  solver_.setTolerance(options.solver_tolerance);
  solver_.setMaxIterations(static_cast<Eigen::Index>(std::max<std::size_t>(100, n)));
}

void RadiusSolver::set_contact(const std::vector<char>& contact) {
  if (ready_ && contact == contact_) return;
  for (std::size_t i = 0; i < diagonal_.size(); ++i) *diagonal_[i] = base_diagonal_[i] + (contact[i] ? options_.contact : 0.0);
  solver_.compute(matrix_);  // the Jacobi preconditioner: the inverse diagonal
  contact_ = contact;
  ready_ = true;
}

int RadiusSolver::solve(const Eigen::VectorXd& target, Eigen::VectorXd& radius) {
  const Eigen::Index n = radius.size();
  std::vector<char> contact(static_cast<std::size_t>(n));
  Eigen::VectorXd rhs(n);
  int solves = 0;
  while (solves < options_.max_iterations) {
    for (Eigen::Index i = 0; i < n; ++i) {
      contact[i] = radius[i] > max_radius_[i];
      rhs[i] = options_.expansion * target[i] + (contact[i] ? options_.contact * max_radius_[i] : 0.0);
    }
    set_contact(contact);
    const Eigen::VectorXd next = solver_.solveWithGuess(rhs, radius);
    if (solver_.info() != Eigen::Success)
      throw std::runtime_error("the fitting system did not converge; check the weights (w must be positive)");
    const double change = (next - radius).lpNorm<Eigen::Infinity>();
    radius = next;
    ++solves;
    if (change < tolerance_) break;
  }
  return solves;
}

std::vector<double> RadiusSolver::fit(double initial_radius, int* solves) {
  Eigen::VectorXd radius = Eigen::VectorXd::Constant(max_radius_.size(), initial_radius);
  const double step = options_.step_fraction * initial_radius;
  int count = 0;
  for (int k = 0; k < options_.progressions; ++k) count += solve(progression_target(radius, step), radius);
  if (solves) *solves += count;
  radius = radius.cwiseMin(max_radius_);
  return {radius.data(), radius.data() + radius.size()};
}

Eigen::VectorXd RadiusSolver::progression_target(const Eigen::VectorXd& radius, double step) const {
  // Grow by the step, never aim past the surface.
  if (!options_.neighbour_cap) return radius + (max_radius_ - radius).cwiseMin(step);
  Eigen::VectorXd target(radius.size());
  for (Eigen::Index i = 0; i < radius.size(); ++i) {
    double smallest = radius[i];
    for (Eigen::SparseMatrix<double>::InnerIterator entry(matrix_, i); entry; ++entry)
      smallest = std::min(smallest, radius[entry.row()]);
    const double capped = std::max(0.0, std::min(step, 2 * step - (radius[i] - smallest)));
    target[i] = radius[i] + std::min(max_radius_[i] - radius[i], capped);
  }
  return target;
}

double initial_radius(const TargetMesh& target, const SkeletonElement& element) {
  double sum = 0;
  for (int k = 0; k < element.corner_count(); ++k) sum += target.distance(element.corners[k]);
  return sum / element.corner_count();
}

Primitive fit_primitive(const TargetMesh& target, const SkeletonElement& element, const FitOptions& options) {
  Primitive primitive;
  primitive.element = element;
  primitive.initial_radius = initial_radius(target, element);
  if (!(primitive.initial_radius > 0)) {
    primitive.failure = "the element lies on the surface (ρ0 = 0)";
    return primitive;
  }
  try {
    primitive.shape = make_template(element, primitive.initial_radius, options.templates);
  } catch (const std::invalid_argument& e) {
    primitive.failure = e.what();
    return primitive;
  }
  primitive.max_radius = max_radii(target, primitive.shape, primitive.failure);
  if (!primitive.failure.empty()) return primitive;
  RadiusSolver solver(primitive.shape.faces, primitive.max_radius, options, options.tolerance * target.scale());
  primitive.radius = solver.fit(primitive.initial_radius, &primitive.solves);
  primitive.fitted = true;
  return primitive;
}

std::vector<Primitive> fit_primitives(const TargetMesh& target, const std::vector<SkeletonElement>& elements,
                                      const FitOptions& options) {
  std::vector<Primitive> primitives(elements.size());
  tbb::parallel_for(std::size_t{0}, elements.size(),
                    [&](std::size_t i) { primitives[i] = fit_primitive(target, elements[i], options); });
  return primitives;
}

}  // namespace medax::msd
