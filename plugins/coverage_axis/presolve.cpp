#include "presolve.hpp"

#include <medax/services/kdtree.hpp>

#include <algorithm>
#include <cstdint>

namespace medax::coverage_axis {

namespace {

/// The instance restricted to the kept rows and columns, renumbered; `column_of` is mapped along.
void compact(Presolved& p, const std::vector<char>& keep_row, const std::vector<char>& keep_column) {
  std::vector<Index> new_row(p.reduced.rows, 0);
  Index rows = 0;
  for (Index r = 0; r < p.reduced.rows; ++r)
    if (keep_row[r]) new_row[r] = rows++;
  SetCover out;
  out.rows = rows;
  std::vector<Index> column_of;
  for (Index j = 0; j < p.reduced.columns.size(); ++j) {
    if (!keep_column[j]) continue;
    std::vector<Index> column;
    for (Index r : p.reduced.columns[j])
      if (keep_row[r]) column.push_back(new_row[r]);
    out.columns.push_back(std::move(column));
    column_of.push_back(p.column_of[j]);
  }
  p.reduced = std::move(out);
  p.column_of = std::move(column_of);
}

/// Picks the only column of each row that has one; drops those columns and the rows they cover.
bool force_unique_covers(Presolved& p) {
  const auto by_row = row_columns(p.reduced);
  std::vector<char> keep_row(p.reduced.rows, 1), keep_column(p.reduced.columns.size(), 1);
  bool changed = false;
  for (const auto& columns : by_row) {
    if (columns.size() != 1 || !keep_column[columns[0]]) continue;
    const Index j = columns[0];
    keep_column[j] = 0;
    for (Index r : p.reduced.columns[j]) keep_row[r] = 0;
    p.forced.push_back(p.column_of[j]);
    ++p.stats.forced;
    changed = true;
  }
  if (changed) compact(p, keep_row, keep_column);
  return changed;
}

/// `a` is dominated by `b` when a's set is inside b's and b is larger, or equal with a lower index:
/// a strict order, so every chain ends at a kept element.
bool dominated_by(const std::vector<Index>& a, Index ia, const std::vector<Index>& b, Index ib) {
  if (b.size() < a.size() || (b.size() == a.size() && ib > ia)) return false;
  return std::includes(b.begin(), b.end(), a.begin(), a.end());
}

/// The list in `candidates` (indices into `lists`) with the fewest entries.
Index shortest(const std::vector<Index>& candidates, const std::vector<std::vector<Index>>& lists) {
  return *std::min_element(candidates.begin(), candidates.end(),
                           [&](Index x, Index y) { return lists[x].size() < lists[y].size(); });
}

/// The columns as bitsets over the rows, `words` 64-bit words each (fast subset tests).
struct ColumnBits {
  std::size_t words;
  std::vector<std::uint64_t> bits;
  explicit ColumnBits(const SetCover& cover) : words((cover.rows + 63) / 64), bits(cover.columns.size() * words, 0) {
    for (std::size_t j = 0; j < cover.columns.size(); ++j)
      for (Index r : cover.columns[j]) bits[j * words + r / 64] |= std::uint64_t(1) << (r % 64);
  }
  bool subset(Index a, Index b) const {
    for (std::size_t w = 0; w < words; ++w)
      if (bits[a * words + w] & ~bits[b * words + w]) return false;
    return true;
  }
};

/// Removes empty columns and columns whose rows another column covers as well.
bool drop_dominated_columns(Presolved& p) {
  const auto& columns = p.reduced.columns;
  const auto by_row = row_columns(p.reduced);
  const ColumnBits bits(p.reduced);
  std::vector<char> keep_column(columns.size(), 1);
  bool changed = false;
  for (Index a = 0; a < columns.size(); ++a) {
    bool dominated = columns[a].empty();
    if (!dominated) {
      // A dominator covers every row of a, in particular a's row with the fewest columns.
      for (Index b : by_row[shortest(columns[a], by_row)]) {
        const std::size_t na = columns[a].size(), nb = columns[b].size();
        if (b != a && (nb > na || (nb == na && b < a)) && bits.subset(a, b)) {
          dominated = true;
          break;
        }
      }
    }
    if (dominated) {
      keep_column[a] = 0;
      ++p.stats.dominated_columns;
      changed = true;
    }
  }
  if (changed) compact(p, std::vector<char>(p.reduced.rows, 1), keep_column);
  return changed;
}

/// Removes each row whose covering columns include another row's (covering that row covers it).
bool drop_dominated_rows(Presolved& p) {
  const auto& columns = p.reduced.columns;
  const auto by_row = row_columns(p.reduced);
  std::vector<char> keep_row(p.reduced.rows, 1);
  bool changed = false;
  for (Index s = 0; s < by_row.size(); ++s) {
    if (by_row[s].empty()) continue;  // cannot happen on a coverable instance; leave it to the solver
    // s is implied by r when cols(r) ⊆ cols(s); such an r lies in every column of s, so in its shortest.
    for (Index r : columns[shortest(by_row[s], columns)])
      if (r != s && dominated_by(by_row[r], r, by_row[s], s)) {
        keep_row[s] = 0;
        ++p.stats.dominated_rows;
        changed = true;
        break;
      }
  }
  if (changed) compact(p, keep_row, std::vector<char>(columns.size(), 1));
  return changed;
}

}  // namespace

Presolved presolve(const SetCover& cover) {
  Presolved p;
  p.reduced = cover;
  p.column_of.resize(cover.columns.size());
  for (Index j = 0; j < cover.columns.size(); ++j) p.column_of[j] = j;
  bool changed = true;
  while (changed && p.reduced.rows > 0) {
    ++p.stats.rounds;
    changed = force_unique_covers(p);
    changed = drop_dominated_columns(p) || changed;
    changed = drop_dominated_rows(p) || changed;
  }
  if (p.reduced.rows == 0) {
    p.reduced.columns.clear();
    p.column_of.clear();
  }
  std::sort(p.forced.begin(), p.forced.end());
  return p;
}

/// How many nearest centres geometric dominance tries per ball.
constexpr std::size_t kDominanceNeighbours = 16;

std::vector<Index> geometrically_undominated(const Balls& balls, double dilation) {
  const std::size_t n = balls.centres.size();
  if (n == 0) return {};
  const services::PointIndex index(balls.centres);
  std::vector<Index> kept;
  for (Index a = 0; a < n; ++a) {
    const double ra = balls.radii[a] + dilation;
    bool inside_another = false;
    // Only the nearest centres are tried: a pre-filter (a ball inside a far centre's ball is left
    // to the exact column dominance of presolve()), cheap where a radius query would return most balls.
    for (const auto& [b, d] : index.k_nearest(balls.centres[a], kDominanceNeighbours)) {
      if (b == a) continue;
      const double rb = balls.radii[b] + dilation;
      // A tolerance in favour of keeping a (rounding must not drop a ball that pokes out);
      // of identical balls the lowest index stays.
      const bool identical = d == 0 && rb == ra;
      if (identical ? b < a : d + ra + 1e-12 <= rb) {
        inside_another = true;
        break;
      }
    }
    if (!inside_another) kept.push_back(a);
  }
  return kept;
}

}  // namespace medax::coverage_axis
