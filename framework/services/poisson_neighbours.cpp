#include "poisson_neighbours.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <tuple>

namespace medax::services::poisson_detail {

namespace {

constexpr int kBits = 21;  // bits per axis in a packed cell key
constexpr std::int64_t kAxisCells = std::int64_t{1} << kBits;

/// Points bucketed in cubic cells (a spatial hash): the points of cell c are
/// order[start[c] .. start[c + 1]), and an open-addressing table finds a cell from its key.
class CellGrid {
 public:
  CellGrid(const std::vector<Vec3>& points, double radius) {
    lo_ = points.front();
    Vec3 hi = lo_;
    for (const Vec3& p : points) lo_ = lo_.cwiseMin(p), hi = hi.cwiseMax(p);
    // Cells at least `radius` wide, so that a point's neighbours lie in the 27 cells around it;
    // wider when the extent would need more than 2^21 cells along an axis.
    side_ = std::max(radius, (hi - lo_).maxCoeff() / static_cast<double>(kAxisCells - 2));
    std::vector<std::uint64_t> key(points.size());
    tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { key[i] = pack(cell_of(points[i])); });
    order_.resize(points.size());
    std::iota(order_.begin(), order_.end(), Index{0});
    tbb::parallel_sort(order_.begin(), order_.end(),
                       [&](Index a, Index b) { return std::tie(key[a], a) < std::tie(key[b], b); });
    for (std::size_t k = 0; k < order_.size(); ++k)
      if (k == 0 || key[order_[k]] != key[order_[k - 1]]) {
        start_.push_back(k);
        keys_.push_back(key[order_[k]]);
      }
    start_.push_back(order_.size());
    build_table();
  }

  std::size_t cells() const { return keys_.size(); }
  /// The cell of every point.
  std::vector<std::uint32_t> cell_of_points() const {
    std::vector<std::uint32_t> cell(order_.size());
    tbb::parallel_for(std::size_t{0}, cells(), [&](std::size_t c) {
      for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) cell[order_[k]] = static_cast<std::uint32_t>(c);
    });
    return cell;
  }
  /// The non-empty cells among the 27 around cell c (itself included), kNone for the others.
  std::array<std::uint32_t, 27> around(std::size_t c) const {
    const auto centre = coordinates(c);
    std::array<std::uint32_t, 27> out;
    int n = 0;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) out[n++] = find({centre[0] + dx, centre[1] + dy, centre[2] + dz});
    return out;
  }
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::array<std::int64_t, 3> coordinates(std::size_t c) const {
    const std::uint64_t k = keys_[c], mask = kAxisCells - 1;
    return {static_cast<std::int64_t>(k >> (2 * kBits)), static_cast<std::int64_t>((k >> kBits) & mask),
            static_cast<std::int64_t>(k & mask)};
  }
  /// The points of cell c.
  std::pair<const Index*, const Index*> members(std::size_t c) const {
    return {order_.data() + start_[c], order_.data() + start_[c + 1]};
  }
  /// The cell at these coordinates, kNone when it is empty or outside.
  std::uint32_t find(const std::array<std::int64_t, 3>& cell) const {
    for (std::int64_t x : cell)
      if (x < 0 || x >= kAxisCells) return kNone;
    const std::uint64_t key = pack(cell);
    for (std::size_t slot = hash(key);; slot = (slot + 1) & mask_) {
      const std::uint32_t c = table_[slot];
      if (c == kNone || keys_[c] == key) return c;
    }
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>((p.x() - lo_.x()) / side_), static_cast<std::int64_t>((p.y() - lo_.y()) / side_),
            static_cast<std::int64_t>((p.z() - lo_.z()) / side_)};
  }
  static std::uint64_t pack(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0]) << (2 * kBits)) | (static_cast<std::uint64_t>(c[1]) << kBits) |
           static_cast<std::uint64_t>(c[2]);
  }
  std::size_t hash(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  void build_table() {
    int bits = 4;
    while ((std::size_t{1} << bits) < 2 * keys_.size()) ++bits;
    shift_ = 64 - bits;
    mask_ = (std::size_t{1} << bits) - 1;
    table_.assign(std::size_t{1} << bits, kNone);
    for (std::size_t c = 0; c < keys_.size(); ++c) {
      std::size_t slot = hash(keys_[c]);
      while (table_[slot] != kNone) slot = (slot + 1) & mask_;
      table_[slot] = static_cast<std::uint32_t>(c);
    }
  }

  Vec3 lo_;
  double side_ = 1;
  std::vector<Index> order_;
  std::vector<std::size_t> start_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> table_;
  int shift_ = 60;
  std::size_t mask_ = 15;
};

/// Calls visit(i, near) for every point i of cell c, `near` holding (squared distance, j) for
/// every point j != i of the 27 cells around it with |p_i - p_j|² < radius², in no set order.
template <typename Visit>
void for_points_in_cell(const CellGrid& grid, const std::vector<Vec3>& points, std::size_t c, double radius,
                        std::vector<std::pair<double, Index>>& near, const Visit& visit) {
  std::array<std::pair<const Index*, const Index*>, 27> around;
  int n = 0;
  for (std::uint32_t cell : grid.around(c))
    if (cell != CellGrid::kNone) around[n++] = grid.members(cell);
  const double r2 = radius * radius;
  const auto [first, last] = grid.members(c);
  for (const Index* i = first; i != last; ++i) {
    const Vec3& q = points[*i];
    near.clear();
    for (int k = 0; k < n; ++k)
      for (const Index* j = around[k].first; j != around[k].second; ++j) {
        if (*j == *i) continue;
        const Vec3& p = points[*j];
        // Summed in this order, as nanoflann does, so distances match a k-d tree's to the bit.
        const double dx = q.x() - p.x(), dy = q.y() - p.y(), dz = q.z() - p.z();
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < r2) near.emplace_back(d2, *j);
      }
    visit(*i, near);
  }
}

}  // namespace

NeighbourLists neighbours_within(const std::vector<Vec3>& points, double radius,
                                 const std::function<bool(Index, Index)>& related,
                                 const std::function<double(double)>& weigh) {
  NeighbourLists out;
  out.offset.assign(points.size() + 1, 0);
  if (points.empty()) return out;
  const CellGrid grid(points, radius);
  const auto keep = [&](Index i, const std::pair<double, Index>& near) {
    return std::sqrt(near.first) < radius && related(i, near.second);
  };
  // One pass over fixed blocks of cells, each filling its own buffer in the order of its points;
  // then every list is copied to its row.
  constexpr std::size_t kBlock = 64;
  const std::size_t blocks = (grid.cells() + kBlock - 1) / kBlock;
  std::vector<std::vector<std::pair<Index, double>>> found(blocks);
  const auto block_points = [&](std::size_t b, const auto& visit) {
    for (std::size_t c = b * kBlock; c < std::min(grid.cells(), (b + 1) * kBlock); ++c) {
      const auto [first, last] = grid.members(c);
      for (const Index* i = first; i != last; ++i) visit(*i);
    }
  };
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::vector<std::pair<double, Index>> near;
    for (std::size_t c = b * kBlock; c < std::min(grid.cells(), (b + 1) * kBlock); ++c)
      for_points_in_cell(grid, points, c, radius, near, [&](Index i, std::vector<std::pair<double, Index>>& list) {
        std::sort(list.begin(), list.end());
        for (const auto& m : list)
          if (keep(i, m)) {
            found[b].emplace_back(m.second, weigh(std::sqrt(m.first)));
            ++out.offset[i + 1];
          }
      });
  });
  std::partial_sum(out.offset.begin(), out.offset.end(), out.offset.begin());
  out.index.resize(out.offset.back());
  out.value.resize(out.offset.back());
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t from = 0;
    block_points(b, [&](Index i) {
      for (std::size_t at = out.offset[i]; at < out.offset[i + 1]; ++at, ++from)
        std::tie(out.index[at], out.value[at]) = found[b][from];
    });
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
