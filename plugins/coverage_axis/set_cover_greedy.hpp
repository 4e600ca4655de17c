#pragma once
// Greedy set covers: the textbook one (warm start of the exact solve) and Coverage Axis++'s
// scored selection (Wang et al. 2024, §2.5 of the notes; the authors' `heuristic_alg`).
#include "coverage_matrix.hpp"

#include <string>

namespace medax::coverage_axis {

/// Textbook greedy: repeatedly the column covering the most uncovered rows (lowest index on ties),
/// until every row is covered.
std::vector<Index> textbook_greedy(const SetCover& cover);

/// CA++'s centrality term, as the authors' `penalty` argument.
enum class Penalty {
  Ratio,        ///< '' (default): s −= λ_c · 0.1 · max r / r_i, not standardised
  Standardized  ///< 'stand': s −= λ_c · z(1 / r_i)
};

struct GreedyOptions {
  double lambda_uniformity = 1;  ///< λ_u
  double lambda_centrality = 1;  ///< λ_c
  Penalty penalty = Penalty::Ratio;
  std::size_t target = 0;        ///< K: stop after K spheres; 0 = until every row is covered
};

/// CA++: each step picks argmax z(new coverage) + λ_u z(distance to the selection) − centrality
/// among the unselected (first on ties; z over all candidates as the authors do, sample std, 0
/// when the std is 0). Stops when
/// every row is covered or at `target`. `balls` are the candidates of the columns (undilated).
std::vector<Index> ca_plus_plus(const SetCover& cover, const Balls& balls, const GreedyOptions& options);

}  // namespace medax::coverage_axis
