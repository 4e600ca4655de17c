#include "poisson_neighbours.hpp"

#include "poisson_grid.hpp"
#include "uninitialised.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
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

/// The fixed-radius search from the points of one cell: the points of the 27 cells around it
/// (itself included), coordinates apart, so that the distances from a point to all of them are
/// computed in one vectorised loop.
class Surroundings {
 public:
  Surroundings(const std::vector<Vec3>& at, const std::vector<Vec3>& normal, double radius, const NormalRule& rule)
      : at_(at), normal_(normal), radius_(radius), rule_(rule) {}

  /// Gathers the points of the cells `around` (CellGrid::around).
  void gather(const CellGrid& grid, const std::array<std::uint32_t, 27>& around) {
    x_.clear(), y_.clear(), z_.clear(), position_.clear();
    for (std::uint32_t cell : around) {
      if (cell == CellGrid::kNone) continue;
      const auto [begin, end] = grid.range(cell);
      for (std::size_t j = begin; j < end; ++j) {
        x_.push_back(at_[j].x()), y_.push_back(at_[j].y()), z_.push_back(at_[j].z());
        position_.push_back(static_cast<Index>(j));
      }
    }
    d2_.resize(x_.size());
  }
  /// Calls found(j, d2) for every gathered point j with |p_k - p_j| < radius and agreeing normals
  /// (k: a point of the gathered cell).
  template <typename F>
  void near(std::size_t k, const F& found) {
    const double qx = at_[k].x(), qy = at_[k].y(), qz = at_[k].z(), r2 = radius_ * radius_;
    const std::size_t n = x_.size();
    for (std::size_t i = 0; i < n; ++i) {
      // Summed in this order, as nanoflann does, so distances match a k-d tree's to the bit.
      const double dx = qx - x_[i], dy = qy - y_[i], dz = qz - z_[i];
      d2_[i] = dx * dx + dy * dy + dz * dz;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!(d2_[i] < r2)) continue;
      const std::size_t j = position_[i];
      if (j != k && std::sqrt(d2_[i]) < radius_ && rule_.agree(normal_[k], normal_[j])) found(j, d2_[i]);
    }
  }

 private:
  const std::vector<Vec3>& at_;
  const std::vector<Vec3>& normal_;
  double radius_;
  const NormalRule& rule_;
  std::vector<double> x_, y_, z_, d2_;
  std::vector<Index> position_;
};

/// The cells around every cell (CellGrid::around), looked up once for the two passes.
using Neighbourhoods = std::vector<std::array<std::uint32_t, 27>>;

/// Calls row(search, k) for every grid position k, cell by cell in parallel, `search` holding the
/// points around k's cell.
template <typename F>
void for_each_point(const CellGrid& grid, const Neighbourhoods& around, const Surroundings& prototype, const F& row) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, grid.cells()), [&](const tbb::blocked_range<std::size_t>& cells) {
    Surroundings search = prototype;
    for (std::size_t c = cells.begin(); c != cells.end(); ++c) {
      search.gather(grid, around[c]);
      const auto [begin, end] = grid.range(c);
      for (std::size_t k = begin; k < end; ++k) row(search, k);
    }
  });
}

/// The length of every row: count[k + 1] for grid position k.
void count_rows(const CellGrid& grid, const Neighbourhoods& around, const Surroundings& prototype,
                std::vector<std::size_t>& count) {
  for_each_point(grid, around, prototype, [&](Surroundings& search, std::size_t k) {
    std::size_t n = 0;
    search.near(k, [&n](std::size_t, double) { ++n; });
    count[k + 1] = n;
  });
}

/// Each row in place (closest first, ties by candidate index) with its values, and each row's
/// values summed in row order.
void fill_rows(const CellGrid& grid, const Neighbourhoods& around, const Surroundings& prototype,
               const EliminationWeight& weigh, NeighbourGraph& out) {
  tbb::enumerable_thread_specific<std::vector<Near>> scratch;
  for_each_point(grid, around, prototype, [&](Surroundings& search, std::size_t k) {
    std::vector<Near>& near = scratch.local();
    near.clear();
    search.near(k, [&](std::size_t j, double d2) { near.push_back({d2, out.original[j], static_cast<Index>(j)}); });
    std::sort(near.begin(), near.end());
    double sum = 0;
    std::size_t at_row = out.offset[k];
    for (const Near& m : near) {
      const double value = weigh(std::sqrt(m.d2));
      out.index[at_row] = m.k;
      out.value[at_row++] = value;
      sum += value;
    }
    out.sum[k] = sum;
  });
}

}  // namespace

NeighbourGraph neighbours_within(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, double radius,
                                 const NormalRule& rule, const EliminationWeight& weigh) {
  NeighbourGraph out;
  out.offset.assign(points.size() + 1, 0);
  if (points.empty()) return out;
  const CellGrid grid(points, radius);
  out.original = grid.order();
  const std::vector<Vec3> at = in_grid_order(points, out.original), normal = in_grid_order(normals, out.original);
  // Two passes over the cells, the rows' lengths and then the rows in place: the rows are written
  // once, where they stay (no per-block copies of them to gather).
  const Surroundings search(at, normal, radius, rule);
  Neighbourhoods around(grid.cells());
  tbb::parallel_for(std::size_t{0}, grid.cells(), [&](std::size_t c) { around[c] = grid.around(c); });
  count_rows(grid, around, search, out.offset);
  std::partial_sum(out.offset.begin(), out.offset.end(), out.offset.begin());
  out.index = uninitialised_array<Index>(out.offset.back());
  out.value = uninitialised_array<double>(out.offset.back());
  out.sum.resize(points.size());
  fill_rows(grid, around, search, weigh, out);
  return out;
}

std::vector<Index> dart_throwing(const std::vector<Vec3>& points, double radius,
                                 const std::function<bool(Index, Index)>& related, std::size_t every,
                                 const std::function<void(double)>& done) {
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
  const auto conflicts = [&](std::size_t i) {
    const Vec3& q = points[i];
    for (std::uint32_t c : around[cell[i]]) {
      if (c == CellGrid::kNone) continue;
      for (Index j = first[c]; j != kEnd; j = next[j])
        if ((points[j] - q).squaredNorm() < r2 && related(static_cast<Index>(i), j)) return true;
    }
    return false;
  };
  // The points go in batches of `every`. A point of a batch that conflicts with one kept before
  // the batch is out whatever comes before it in the batch: those tests run in parallel (the lists
  // are only read). The others are then tested in order against every point kept so far, the
  // batch's included: the same points as one pass in order, most of the tests done in parallel
  // once the surface is mostly covered.
  every = std::max<std::size_t>(every, 1);
  std::vector<char> out_early(every);
  for (std::size_t begin = 0; begin < points.size(); begin += every) {
    const std::size_t end = std::min(points.size(), begin + every);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) out_early[i - begin] = conflicts(i);
    });
    for (std::size_t i = begin; i < end; ++i) {
      if (out_early[i - begin] || conflicts(i)) continue;
      kept.push_back(static_cast<Index>(i));
      next[i] = first[cell[i]];
      first[cell[i]] = static_cast<Index>(i);
    }
    if (end < points.size()) done(static_cast<double>(end) / static_cast<double>(points.size()));
  }
  return kept;
}

}  // namespace medax::services::poisson_detail
