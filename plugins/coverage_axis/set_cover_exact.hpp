#pragma once
// Minimum set cover, solved exactly (Coverage Axis, Dou et al. 2022): presolve, greedy warm
// start, LP bound, then CBC branch and cut with a time limit. CBC stays out of this header.
#include "presolve.hpp"

#include <functional>

namespace medax::coverage_axis {

struct ExactOptions {
  double time_limit = 1000;  ///< seconds of branch and cut (the authors' code: 1000)
  bool presolve = true;
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
  std::size_t warm_start = 0;   ///< size of the greedy cover given to CBC
  PresolveStats presolve;
  double seconds_presolve = 0, seconds_lp = 0, seconds_solve = 0;
};

/// A minimum cover of `cover` (every row must be coverable).
ExactResult solve_exact(const SetCover& cover, const ExactOptions& options, const SolveProgress& progress = {});

}  // namespace medax::coverage_axis
