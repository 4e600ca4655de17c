#include "set_cover_local_search.hpp"

#include <medax/services/blocks.hpp>

#include <algorithm>
#include <random>

namespace medax::coverage_axis {

namespace {

constexpr Index kNoColumn = static_cast<Index>(-1);

/// What every run reads: the columns of each row, and the columns sharing a row with each column.
struct Adjacency {
  std::vector<std::vector<Index>> by_row;
  std::vector<std::vector<Index>> neighbours;  ///< distinct, the column itself included

  explicit Adjacency(const SetCover& cover) : by_row(row_columns(cover)), neighbours(cover.columns.size()) {
    std::vector<Index> seen(cover.columns.size(), kNoColumn);
    for (Index j = 0; j < cover.columns.size(); ++j)
      for (Index r : cover.columns[j])
        for (Index k : by_row[r])
          if (seen[k] != j) seen[k] = j, neighbours[j].push_back(k);
  }
};

/// RWLS's state: the current (partial) selection S, how often each row is covered, the row
/// weights and every column's score, i.e. the weight S gains by adding a column outside S
/// (its uncovered rows) or loses by removing one in S (its rows no other column of S covers).
class RowWeightingSearch {
 public:
  RowWeightingSearch(const SetCover& cover, const Adjacency& adjacency)
      : cover_(cover),
        by_row_(adjacency.by_row),
        neighbours_(adjacency.neighbours),
        position_(cover.columns.size(), kOut),
        score_(cover.columns.size(), 0),
        stamp_(cover.columns.size(), 0),
        can_add_(cover.columns.size(), 1),
        count_(cover.rows, 0),
        cover_xor_(cover.rows, 0),
        weight_(cover.rows, 1),
        uncovered_at_(cover.rows, kOut) {
    for (Index r = 0; r < cover.rows; ++r) mark_uncovered(r);
    for (Index j = 0; j < cover.columns.size(); ++j) score_[j] = static_cast<std::int64_t>(cover.columns[j].size());
  }

  const std::vector<Index>& selection() const { return selection_; }
  bool covers_all() const { return uncovered_.empty(); }
  bool selected(Index j) const { return position_[j] != kOut; }

  void add(Index j, std::size_t step) {
    position_[j] = selection_.size();
    selection_.push_back(j);
    score_[j] = -score_[j];  // its uncovered rows become the rows only it covers
    stamp_[j] = step;
    for (Index r : cover_.columns[j]) {
      if (count_[r] == 0) {
        mark_covered(r);
        shift_others(r, j, -weight_[r]);  // no longer a gain for the other columns of r
      } else if (count_[r] == 1) {
        score_[cover_xor_[r]] += weight_[r];  // its removal no longer uncovers r
      }
      ++count_[r];
      cover_xor_[r] ^= j;
    }
    allow_neighbours(j);
  }

  void remove(Index j, std::size_t step) {
    const std::size_t at = position_[j];
    selection_[at] = selection_.back();
    position_[selection_[at]] = at;
    selection_.pop_back();
    position_[j] = kOut;
    score_[j] = -score_[j];  // the rows only it covered become its uncovered rows
    stamp_[j] = step;
    for (Index r : cover_.columns[j]) {
      --count_[r];
      cover_xor_[r] ^= j;
      if (count_[r] == 0) {
        mark_uncovered(r);
        shift_others(r, j, weight_[r]);
      } else if (count_[r] == 1) {
        score_[cover_xor_[r]] -= weight_[r];
      }
    }
    allow_neighbours(j);
    can_add_[j] = 0;  // configuration checking: not back before a neighbour changes
  }

  /// The column of S with the highest score (the cheapest to remove), the least recently moved
  /// on ties, other than `tabu`.
  Index best_to_remove(Index tabu) const {
    Index best = kNoColumn;
    for (Index j : selection_)
      if (j != tabu && (best == kNoColumn || better(j, best))) best = j;
    return best == kNoColumn ? tabu : best;
  }

  /// The column covering row r with the highest score that configuration checking allows (any
  /// of r's columns when it allows none), the least recently moved on ties.
  Index best_to_add(Index r) const {
    Index best = kNoColumn;
    for (Index j : by_row_[r])
      if (can_add_[j] && (best == kNoColumn || better(j, best))) best = j;
    if (best == kNoColumn)
      for (Index j : by_row_[r])
        if (best == kNoColumn || better(j, best)) best = j;
    return best;
  }

  Index uncovered_row(std::mt19937_64& rng) const { return uncovered_[rng() % uncovered_.size()]; }

  /// Every uncovered row weighs one more, so rows that stay uncovered pull harder.
  void weigh_uncovered() {
    for (Index r : uncovered_) {
      ++weight_[r];
      for (Index j : by_row_[r]) ++score_[j];
    }
  }

 private:
  static constexpr std::size_t kOut = static_cast<std::size_t>(-1);

  bool better(Index a, Index b) const { return score_[a] > score_[b] || (score_[a] == score_[b] && stamp_[a] < stamp_[b]); }

  void mark_uncovered(Index r) {
    uncovered_at_[r] = uncovered_.size();
    uncovered_.push_back(r);
  }
  void mark_covered(Index r) {
    const std::size_t at = uncovered_at_[r];
    uncovered_[at] = uncovered_.back();
    uncovered_at_[uncovered_[at]] = at;
    uncovered_.pop_back();
    uncovered_at_[r] = kOut;
  }
  void shift_others(Index r, Index except, std::int64_t delta) {
    for (Index k : by_row_[r])
      if (k != except) score_[k] += delta;
  }
  /// Configuration checking: a change of j lets its neighbours be added again.
  void allow_neighbours(Index j) {
    for (Index k : neighbours_[j]) can_add_[k] = 1;
  }

  const SetCover& cover_;
  const std::vector<std::vector<Index>>& by_row_;
  const std::vector<std::vector<Index>>& neighbours_;
  std::vector<std::size_t> position_;  ///< index in selection_, or kOut
  std::vector<Index> selection_;
  std::vector<std::int64_t> score_;
  std::vector<std::size_t> stamp_;     ///< step of the column's last move
  std::vector<char> can_add_;
  std::vector<std::uint32_t> count_;   ///< columns of S covering each row
  std::vector<Index> cover_xor_;       ///< XOR of those columns: the sole one when count_ is 1
  std::vector<std::int64_t> weight_;
  std::vector<Index> uncovered_;
  std::vector<std::size_t> uncovered_at_;
};

/// One run of RWLS from `start` with its own random row choices.
std::vector<Index> search_once(const SetCover& cover, const Adjacency& adjacency,
                               const std::vector<Index>& start, std::size_t steps, std::size_t lower_bound,
                               std::uint64_t seed) {
  RowWeightingSearch search(cover, adjacency);
  for (Index j : start) search.add(j, 0);
  std::vector<Index> best = search.selection();
  // On a cover: keep it if smaller, then drop the cheapest column, to look for one a column smaller.
  const auto shrink = [&](std::size_t step) {
    while (search.covers_all() && !search.selection().empty()) {
      if (search.selection().size() < best.size()) best = search.selection();
      if (best.size() <= lower_bound) return;
      search.remove(search.best_to_remove(kNoColumn), step);
    }
  };
  shrink(0);  // the start without its redundant columns
  std::mt19937_64 rng(seed);
  Index tabu = kNoColumn;
  for (std::size_t step = 1; step <= steps; ++step) {
    if (search.covers_all() || search.selection().empty() || best.size() <= lower_bound) break;
    // A swap at the same size: drop the cheapest column, add the best one for a random uncovered row.
    search.remove(search.best_to_remove(tabu), step);
    tabu = search.best_to_add(search.uncovered_row(rng));
    search.add(tabu, step);
    search.weigh_uncovered();
    shrink(step);
  }
  std::sort(best.begin(), best.end());
  return best;
}

}  // namespace

std::vector<Index> local_search_cover(const SetCover& cover, const std::vector<Index>& start,
                                      const LocalSearchOptions& options) {
  const Adjacency adjacency(cover);
  // No runs: one without steps, which only removes the start's redundant columns.
  const std::size_t steps = options.runs == 0 ? 0 : options.iterations;
  std::vector<std::vector<Index>> found(std::max<std::size_t>(options.runs, 1));
  services::for_blocks(found.size(), 1, true, [&](std::size_t run, std::size_t, std::size_t) {
    found[run] = search_once(cover, adjacency, start, steps, options.lower_bound, options.seed + run);
  });
  // The smallest cover, of the lowest run on ties: the same whatever the thread count.
  return *std::min_element(found.begin(), found.end(),
                           [](const auto& a, const auto& b) { return a.size() < b.size(); });
}

}  // namespace medax::coverage_axis
