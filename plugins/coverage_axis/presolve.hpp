#pragma once
// Set-cover presolve (Coverage Axis, as the authors' CA_GPU/scp_exact.py does it): reductions
// that keep the optimum value, applied to a fixpoint. Every reduction keeps at least one optimal
// cover: forced picks are in every cover, a dominated column can be swapped for its dominator,
// and a row whose columns include another row's columns is covered whenever that row is.
#include "coverage_matrix.hpp"

namespace medax::coverage_axis {

struct PresolveStats {
  std::size_t forced = 0;             ///< columns picked because a row has no other
  std::size_t dominated_columns = 0;  ///< duplicate, empty or subset columns removed
  std::size_t dominated_rows = 0;     ///< rows implied by another row, removed
  std::size_t rounds = 0;
  std::size_t rows = 0, columns = 0, nonzeros = 0;  ///< the program left to solve (set by solve_exact)
};

struct Presolved {
  SetCover reduced;              ///< what is left to solve, renumbered
  std::vector<Index> column_of;  ///< reduced column -> column of the input
  std::vector<Index> forced;     ///< columns of the input every optimal cover here contains
  PresolveStats stats;
};

/// Forced picks, duplicate/dominated columns and dominated rows, repeated until nothing changes.
Presolved presolve(const SetCover& cover);

/// Geometric dominance, a cheap pre-filter: drops a when the dilated ball of one of its 16 nearest
/// centres b contains a's (‖c_a − c_b‖ + r̃_a ≤ r̃_b; of identical balls the lowest index stays);
/// presolve()'s column dominance catches the rest. Returns the kept candidates, ascending.
std::vector<Index> geometrically_undominated(const Balls& balls, double dilation);

}  // namespace medax::coverage_axis
