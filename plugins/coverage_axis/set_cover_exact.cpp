#include "set_cover_exact.hpp"

#include "set_cover_greedy.hpp"
#include "set_cover_local_search.hpp"

#include <CbcEventHandler.hpp>
#include <CbcModel.hpp>
#include <CbcSolver.hpp>
#include <ClpSolve.hpp>
#include <CoinPackedMatrix.hpp>
#include <OsiClpSolverInterface.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <string>

namespace medax::coverage_axis {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// min Σx subject to (each row covered at least once), 0 ≤ x ≤ 1, every x integer.
OsiClpSolverInterface set_cover_program(const SetCover& cover) {
  CoinPackedMatrix matrix(true, 0, 0);  // column ordered
  matrix.setDimensions(static_cast<int>(cover.rows), 0);
  for (const auto& column : cover.columns) {
    const std::vector<int> rows(column.begin(), column.end());
    const std::vector<double> ones(rows.size(), 1.0);
    matrix.appendCol(static_cast<int>(rows.size()), rows.data(), ones.data());
  }
  const std::size_t n = cover.columns.size();
  const std::vector<double> lower(n, 0.0), upper(n, 1.0), cost(n, 1.0);
  const std::vector<double> row_lower(cover.rows, 1.0), row_upper(cover.rows, COIN_DBL_MAX);
  OsiClpSolverInterface program;
  program.messageHandler()->setLogLevel(0);
  // Dual simplex without presolve for the initial LP: Clp's automatic choice (Idiot crash and
  // crossover) crashes on some of these programs (CBC 2.10.8, seen on joint.off).
  ClpSolve lp_options;
  lp_options.setSolveType(ClpSolve::useDual);
  lp_options.setPresolveType(ClpSolve::presolveOff);
  program.setSolveOptions(lp_options);
  program.loadProblem(matrix, lower.data(), upper.data(), cost.data(), row_lower.data(), row_upper.data());
  for (std::size_t j = 0; j < n; ++j) program.setInteger(static_cast<int>(j));
  return program;
}

/// Forwards CBC's node events to the caller's progress callback, a few times a second at most,
/// with the forced picks added to CBC's incumbent and bound.
class ProgressEvents : public CbcEventHandler {
 public:
  ProgressEvents(SolveProgress progress, Clock::time_point start, double forced)
      : progress_(std::move(progress)), start_(start), last_(start), forced_(forced) {}
  CbcEventHandler* clone() const override { return new ProgressEvents(*this); }
  CbcAction event(CbcEvent which) override {
    if (!progress_ || (which != node && which != solution)) return noAction;
    if (which == node && seconds_since(last_) < 0.25) return noAction;
    last_ = Clock::now();
    const bool go_on =
        progress_(seconds_since(start_), forced_ + model_->getObjValue(), forced_ + model_->getBestPossibleObjValue());
    return go_on ? noAction : stop;
  }

 private:
  SolveProgress progress_;
  Clock::time_point start_, last_;
  double forced_;
};

/// The LP relaxation's optimum (a lower bound on the cover size).
double lp_relaxation(const OsiClpSolverInterface& program) {
  OsiClpSolverInterface lp(program);
  lp.messageHandler()->setLogLevel(0);
  lp.initialSolve();
  return lp.isProvenOptimal() ? lp.getObjValue() : 0.0;
}

struct Branched {
  std::vector<Index> chosen;
  bool proven = false;
  double bound = 0;
  std::size_t nodes = 0;
};

/// CBC's standard branch and cut (its command-line driver's default cuts and preprocessing, one
/// thread, wall-clock limit) from the warm-start cover; columns with x > 0.5 (rounded, not truncated).
/// CBC takes its cutoff (start − 1, the objective being integral) from the start by itself. Its
/// primal heuristics are off: the local search has found the optimum on every model measured, so
/// what is left is the proof, and the heuristics' time per node halves it on fertility
/// (docs/plugins/coverage_axis.md, "Measured").
Branched branch_and_cut(OsiClpSolverInterface program, const std::vector<Index>& warm, const ExactOptions& options,
                        const SolveProgress& progress, std::size_t forced) {
  std::vector<std::pair<std::string, double>> start;
  for (int j = 0; j < program.getNumCols(); ++j) {
    program.setColName(j, "x" + std::to_string(j));
    start.emplace_back("x" + std::to_string(j), 0.0);
  }
  for (Index j : warm) start[j].second = 1.0;
  CbcModel model(program);
  CbcMain0(model);
  model.setMIPStart(start);
  const ProgressEvents events(progress, Clock::now(), static_cast<double>(forced));
  model.passInEventHandler(&events);
  const std::string seconds = std::to_string(options.time_limit);
  const char* argv[] = {"medax", "-log",    "0", "-timeMode", "elapsed", "-sec",  seconds.c_str(),
                        "-threads", "0", "-heuristicsOnOff", "off", "-solve",   "-quit"};
  CbcMain1(static_cast<int>(std::size(argv)), argv, model);
  Branched out;
  const double* x = model.bestSolution();
  for (int j = 0; x && j < model.getNumCols(); ++j)
    if (x[j] > 0.5) out.chosen.push_back(static_cast<Index>(j));
  if (!x) out.chosen = warm;
  out.proven = model.isProvenOptimal() && !model.isSecondsLimitReached();
  out.bound = model.getBestPossibleObjValue();
  out.nodes = static_cast<std::size_t>(model.getNodeCount());
  return out;
}

/// Adds the input columns of reduced columns `columns` to `chosen`, keeping it ascending.
void add_columns(std::vector<Index>& chosen, const std::vector<Index>& columns, const Presolved& p) {
  for (Index j : columns) chosen.push_back(p.column_of[j]);
  std::sort(chosen.begin(), chosen.end());
}

/// Fills the certificate fields: proven when CBC says so or the LP bound rounds up to the size.
void certify(ExactResult& r, bool cbc_proven, double cbc_bound) {
  const double size = static_cast<double>(r.chosen.size());
  r.lower_bound = std::max(r.lp_bound, std::isfinite(cbc_bound) ? cbc_bound : 0.0);
  const double rounded = std::ceil(r.lower_bound - 1e-6);
  r.proven_optimal = cbc_proven || std::ceil(r.lp_bound - 1e-6) == size;
  r.gap = r.proven_optimal || size == 0 ? 0.0 : (size - rounded) / size;
}

}  // namespace

ExactResult solve_exact(const SetCover& cover, const ExactOptions& options, const SolveProgress& progress) {
  ExactResult r;
  auto t = Clock::now();
  Presolved p;
  if (options.presolve) {
    p = presolve(cover);
  } else {
    p.reduced = cover;
    for (Index j = 0; j < cover.columns.size(); ++j) p.column_of.push_back(j);
  }
  r.presolve = p.stats;
  r.presolve.rows = p.reduced.rows;
  r.presolve.columns = p.reduced.columns.size();
  for (const auto& column : p.reduced.columns) r.presolve.nonzeros += column.size();
  r.seconds_presolve = seconds_since(t);
  r.chosen = p.forced;
  if (p.reduced.rows == 0) {
    r.lp_bound = static_cast<double>(r.chosen.size());
    certify(r, true, r.lp_bound);
    return r;
  }
  t = Clock::now();
  const OsiClpSolverInterface program = set_cover_program(p.reduced);
  const double lp = lp_relaxation(program);
  r.lp_bound = static_cast<double>(p.forced.size()) + lp;
  r.seconds_lp = seconds_since(t);
  t = Clock::now();
  const std::vector<Index> greedy = textbook_greedy(p.reduced);
  LocalSearchOptions search;
  search.runs = options.search_runs;
  search.iterations = options.search_iterations;
  search.lower_bound = static_cast<std::size_t>(std::ceil(lp - 1e-6));
  const std::vector<Index> warm = local_search_cover(p.reduced, greedy, search);
  r.greedy = p.forced.size() + greedy.size();
  r.warm_start = p.forced.size() + warm.size();
  r.seconds_search = seconds_since(t);
  if (warm.size() <= search.lower_bound) {  // the LP bound proves the warm start optimal
    add_columns(r.chosen, warm, p);
    certify(r, false, r.lp_bound);
    return r;
  }
  t = Clock::now();
  const Branched b = branch_and_cut(program, warm, options, progress, p.forced.size());
  r.seconds_solve = seconds_since(t);
  r.nodes = b.nodes;
  add_columns(r.chosen, b.chosen, p);
  certify(r, b.proven, static_cast<double>(p.forced.size()) + b.bound);
  return r;
}

}  // namespace medax::coverage_axis
