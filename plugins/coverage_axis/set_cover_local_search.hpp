#pragma once
// A small cover by local search, the warm start of the exact solve: row-weighting local search
// for unicost set cover (RWLS, Gao, Weise and Li, "An efficient local search heuristic with row
// weighting for the unicost set covering problem", EJOR 246(3), 2015). Branch and cut prunes a
// node only when its bound is above the incumbent minus one, so starting it at the optimum
// leaves it the proof alone (docs/plugins/coverage_axis.md, "Measured").
#include "coverage_matrix.hpp"

#include <cstdint>

namespace medax::coverage_axis {

struct LocalSearchOptions {
  std::size_t runs = 8;            ///< independent runs (in parallel), seeds seed, seed + 1, …; 0: no steps
  std::size_t iterations = 25000;  ///< swap steps per run; a count, not a time, so the result is reproducible
  std::size_t lower_bound = 0;     ///< a run stops as soon as it finds a cover this small (no smaller one exists)
  std::uint64_t seed = 0;          ///< of the random uncovered row each step
};

/// Starting from `start` (a cover of every row), each run repeatedly drops a column and swaps
/// columns under row weights to find a cover one smaller; returns the smallest cover any run saw
/// (ascending; the lowest run's on ties). Several short runs rather than one long one, because
/// the steps a run needs to reach the optimum are heavy-tailed (docs: "Measured"). Never larger
/// than `start` without its redundant columns; the same for any thread count, given the seed.
std::vector<Index> local_search_cover(const SetCover& cover, const std::vector<Index>& start,
                                      const LocalSearchOptions& options);

}  // namespace medax::coverage_axis
