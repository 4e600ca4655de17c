#include "set_cover_greedy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace medax::coverage_axis {

std::vector<Index> textbook_greedy(const SetCover& cover) {
  std::vector<char> covered(cover.rows, 0);
  std::size_t remaining = cover.rows;
  std::vector<Index> chosen;
  while (remaining > 0) {
    Index best = 0;
    std::size_t best_gain = 0;
    for (Index j = 0; j < cover.columns.size(); ++j) {
      std::size_t gain = 0;
      for (Index r : cover.columns[j]) gain += covered[r] ? 0 : 1;
      if (gain > best_gain) best = j, best_gain = gain;
    }
    if (best_gain == 0) break;  // the rest is uncoverable
    for (Index r : cover.columns[best]) remaining -= covered[r] ? 0 : 1, covered[r] = 1;
    chosen.push_back(best);
  }
  return chosen;
}

namespace {

/// (x − mean) / std with the sample std (ddof 1); all zeros when the std is 0.
std::vector<double> standardized(const std::vector<double>& x) {
  std::vector<double> z(x.size(), 0.0);
  if (x.size() < 2) return z;
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
  double sum2 = 0;
  for (double v : x) sum2 += (v - mean) * (v - mean);
  const double sd = std::sqrt(sum2 / (x.size() - 1));
  if (!(sd > 0) || !std::isfinite(sd)) return z;
  for (std::size_t i = 0; i < x.size(); ++i) z[i] = (x[i] - mean) / sd;
  return z;
}

/// The centrality penalty of every candidate (subtracted from the score, times λ_c).
std::vector<double> centrality_penalty(const Balls& balls, Penalty penalty) {
  std::vector<double> inverse(balls.radii.size());
  for (std::size_t i = 0; i < inverse.size(); ++i) inverse[i] = 1.0 / std::max(balls.radii[i], 1e-12);
  if (penalty == Penalty::Standardized) return standardized(inverse);
  const double max_radius = balls.radii.empty() ? 0 : *std::max_element(balls.radii.begin(), balls.radii.end());
  for (double& v : inverse) v *= 0.1 * max_radius;
  return inverse;
}

/// The CA++ selection state: new coverage and distance to the selection of every candidate.
struct GreedyState {
  std::vector<double> coverage;
  std::vector<double> distance;
  std::vector<char> covered, selected;
  std::size_t remaining;
};

/// Index of the unselected candidate with the highest score (first on ties).
Index best_candidate(const GreedyState& s, const std::vector<double>& penalty, const GreedyOptions& o,
                     bool any_selected) {
  const std::vector<double> z_coverage = standardized(s.coverage);
  const std::vector<double> z_distance = any_selected ? standardized(s.distance) : std::vector<double>{};
  Index best = 0;
  double best_score = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < s.coverage.size(); ++i) {
    if (s.selected[i]) continue;
    double score = z_coverage[i] - o.lambda_centrality * penalty[i];
    if (any_selected) score += o.lambda_uniformity * z_distance[i];
    if (score > best_score) best = i, best_score = score;
  }
  return best;
}

/// Adds candidate `pick`: its rows are covered, the others' new coverage and distances updated.
void select(GreedyState& s, Index pick, const SetCover& cover, const std::vector<std::vector<Index>>& by_row,
            const Balls& balls) {
  s.selected[pick] = 1;
  for (Index r : cover.columns[pick]) {
    if (s.covered[r]) continue;
    s.covered[r] = 1;
    --s.remaining;
    for (Index c : by_row[r]) s.coverage[c] -= 1;
  }
  for (Index i = 0; i < s.distance.size(); ++i)
    s.distance[i] = std::min(s.distance[i], (balls.centres[i] - balls.centres[pick]).norm());
}

}  // namespace

std::vector<Index> ca_plus_plus(const SetCover& cover, const Balls& balls, const GreedyOptions& options) {
  const std::size_t n = cover.columns.size();
  const auto by_row = row_columns(cover);
  const std::vector<double> penalty = centrality_penalty(balls, options.penalty);
  GreedyState s{std::vector<double>(n), std::vector<double>(n, std::numeric_limits<double>::infinity()),
                std::vector<char>(cover.rows, 0), std::vector<char>(n, 0), cover.rows};
  for (Index i = 0; i < n; ++i) s.coverage[i] = static_cast<double>(cover.columns[i].size());
  std::vector<Index> chosen;
  while (s.remaining > 0 && chosen.size() < n && (options.target == 0 || chosen.size() < options.target)) {
    const Index pick = best_candidate(s, penalty, options, !chosen.empty());
    select(s, pick, cover, by_row, balls);
    chosen.push_back(pick);
  }
  return chosen;
}

}  // namespace medax::coverage_axis
