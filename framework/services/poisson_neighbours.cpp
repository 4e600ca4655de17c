#include "poisson_neighbours.hpp"

#include "poisson_grid.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace medax::services::poisson_detail {

namespace {

/// A neighbour found by the search: squared distance, candidate index (for ties), grid position.
struct Near {
  double d2;
  Index original, k;
  bool operator<(const Near& o) const { return d2 < o.d2 || (d2 == o.d2 && original < o.original); }
};

/// The rows of the neighbour graph for a run of grid positions, before they are copied into place.
struct Rows {
  std::vector<Index> index;
  std::vector<double> value;
};

/// The graph's rows for the points of cells [first, last): for each, the points of the 27 cells
/// around with |p_k - p_j| < radius and agreeing normals, closest first (ties by candidate index).
/// Counts each row's length in count[k].
void rows_of_cells(const CellGrid& grid, const std::vector<Vec3>& at, const std::vector<Vec3>& normal,
                   const std::vector<Index>& original, std::size_t first, std::size_t last, double radius,
                   const NormalRule& rule, const EliminationWeight& weigh, Rows& rows, std::size_t* count) {
  const double r2 = radius * radius;
  std::vector<Near> near;
  for (std::size_t c = first; c < last; ++c) {
    std::array<std::pair<std::size_t, std::size_t>, 27> around;
    int n = 0;
    for (std::uint32_t cell : grid.around(c))
      if (cell != CellGrid::kNone) around[n++] = grid.range(cell);
    const auto [begin, end] = grid.range(c);
    for (std::size_t k = begin; k < end; ++k) {
      const Vec3& q = at[k];
      near.clear();
      for (int a = 0; a < n; ++a)
        for (std::size_t j = around[a].first; j < around[a].second; ++j) {
          // Summed in this order, as nanoflann does, so distances match a k-d tree's to the bit.
          const double dx = q.x() - at[j].x(), dy = q.y() - at[j].y(), dz = q.z() - at[j].z();
          const double d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < r2 && j != k && std::sqrt(d2) < radius && rule.agree(normal[k], normal[j]))
            near.push_back({d2, original[j], static_cast<Index>(j)});
        }
      std::sort(near.begin(), near.end());
      for (const Near& m : near) {
        rows.index.push_back(m.k);
        rows.value.push_back(weigh(std::sqrt(m.d2)));
      }
      count[k + 1] = near.size();
    }
  }
}

template <typename T>
std::vector<T> gather(const std::vector<T>& values, const std::vector<Index>& order) {
  std::vector<T> out(order.size());
  tbb::parallel_for(std::size_t{0}, order.size(), [&](std::size_t k) { out[k] = values[order[k]]; });
  return out;
}

}  // namespace

NeighbourGraph neighbours_within(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, double radius,
                                 const NormalRule& rule, const EliminationWeight& weigh) {
  NeighbourGraph out;
  out.offset.assign(points.size() + 1, 0);
  if (points.empty()) return out;
  const CellGrid grid(points, radius);
  out.original = grid.order();
  const std::vector<Vec3> at = gather(points, out.original), normal = gather(normals, out.original);
  // One pass over fixed blocks of cells, each filling its own rows (consecutive grid positions);
  // then each block's rows are copied into place.
  constexpr std::size_t kBlock = 64;
  const std::size_t blocks = (grid.cells() + kBlock - 1) / kBlock;
  const auto cells_of = [&](std::size_t b) { return std::pair{b * kBlock, std::min(grid.cells(), (b + 1) * kBlock)}; };
  std::vector<Rows> found(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const auto [first, last] = cells_of(b);
    rows_of_cells(grid, at, normal, out.original, first, last, radius, rule, weigh, found[b], out.offset.data());
  });
  std::partial_sum(out.offset.begin(), out.offset.end(), out.offset.begin());
  out.index.resize(out.offset.back());
  out.value.resize(out.offset.back());
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t at_row = out.offset[grid.range(cells_of(b).first).first];
    std::copy(found[b].index.begin(), found[b].index.end(), out.index.begin() + at_row);
    std::copy(found[b].value.begin(), found[b].value.end(), out.value.begin() + at_row);
    found[b] = {};
  });
  return out;
}

std::vector<Index> dart_throwing(const std::vector<Vec3>& points, double radius,
                                 const std::function<bool(Index, Index)>& related) {
  std::vector<Index> kept;
  if (points.empty()) return kept;
  const CellGrid grid(points, radius);
  const std::vector<std::uint32_t> cell = grid.cell_of_points();
  std::vector<std::array<std::uint32_t, 27>> around(grid.cells());
  tbb::parallel_for(std::size_t{0}, grid.cells(), [&](std::size_t c) { around[c] = grid.around(c); });
  // The kept points of each cell, as linked lists: first[cell], then next[point].
  constexpr Index kEnd = ~Index{0};
  std::vector<Index> first(grid.cells(), kEnd), next(points.size(), kEnd);
  const double r2 = radius * radius;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& q = points[i];
    bool free = true;
    for (std::uint32_t c : around[cell[i]]) {
      if (c == CellGrid::kNone) continue;
      for (Index j = first[c]; j != kEnd && free; j = next[j])
        free = !((points[j] - q).squaredNorm() < r2 && related(static_cast<Index>(i), j));
      if (!free) break;
    }
    if (!free) continue;
    kept.push_back(static_cast<Index>(i));
    next[i] = first[cell[i]];
    first[cell[i]] = static_cast<Index>(i);
  }
  return kept;
}

}  // namespace medax::services::poisson_detail
