#include "split.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace medax::vmas {

std::vector<Index> select_splits(const std::vector<double>& errors, const Adjacency& adjacency,
                                 const SplitRound& round) {
  const std::size_t count = errors.size();
  std::vector<Index> order(count);
  std::iota(order.begin(), order.end(), Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return errors[a] > errors[b]; });
  std::size_t budget = std::min(
      static_cast<std::size_t>(std::ceil(round.fraction * static_cast<double>(count))), round.max_per_round);
  std::vector<char> blocked(count, 0);
  std::vector<Index> chosen;
  for (Index i : order) {
    if (budget == 0) break;
    if (round.count_mode && count + chosen.size() >= round.target) break;
    if (!round.count_mode && errors[i] < round.threshold) break;
    if (blocked[i]) continue;
    for (Index j : adjacency[i]) blocked[j] = 1;
    blocked[i] = 1;
    chosen.push_back(i);
    --budget;
  }
  return chosen;
}

}  // namespace medax::vmas
