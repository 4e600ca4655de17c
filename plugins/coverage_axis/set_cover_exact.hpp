#pragma once
// Minimum set cover, solved exactly (Coverage Axis, Dou et al. 2022): presolve, LP bound, a
// warm start by greedy and local search, then CBC branch and cut with a time limit (skipped when
// the warm start already meets the LP bound). CBC stays out of this header.
#include "presolve.hpp"

#include <functional>

namespace medax::coverage_axis {

struct ExactOptions {
  double time_limit = 1000;  ///< seconds of branch and cut (the authors' code: 1000)
  bool presolve = true;
  std::size_t search_runs = 8;          ///< local-search runs of the warm start (0: greedy only)
  std::size_t search_iterations = 25000;  ///< steps per local-search run
};

/// Called now and then during branch and cut with the seconds spent, the best cover size found
/// and the best lower bound; returning false stops the solve (the best cover so far is kept).
using SolveProgress = std::function<bool(double seconds, double incumbent, double bound)>;

struct ExactResult {
  std::vector<Index> chosen;    ///< columns of the input, ascending; a cover of every row
  double lp_bound = 0;          ///< forced picks + LP relaxation of the reduced instance
  double lower_bound = 0;       ///< the best proven lower bound (LP, or CBC's when higher)
  bool proven_optimal = false;  ///< CBC proved optimality, or ⌈LP − 1e-6⌉ equals the size
  double gap = 0;               ///< (size − ⌈lower bound − 1e-6⌉) / size; 0 when proven
  std::size_t greedy = 0;       ///< size of the textbook greedy cover
  std::size_t warm_start = 0;   ///< size of the cover given to CBC (greedy improved by local search)
  std::size_t nodes = 0;        ///< branch-and-cut nodes (0 when the LP bound proves the warm start)
  PresolveStats presolve;
  double seconds_presolve = 0, seconds_lp = 0, seconds_search = 0, seconds_solve = 0;
};

/// A minimum cover of `cover` (every row must be coverable).
ExactResult solve_exact(const SetCover& cover, const ExactOptions& options, const SolveProgress& progress = {});

}  // namespace medax::coverage_axis
