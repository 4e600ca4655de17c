#pragma once
// A grid of cubic cells over a point set, for the fixed-radius and k-nearest searches of the
// Poisson-disk sampling (private to it). The cells are numbered along a Morton curve and the
// points listed cell by cell, so a search that walks the cells in order reads nearby memory.
#include <medax/geometry.hpp>

#include <tbb/parallel_for.h>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace medax::services::poisson_detail {

/// Points bucketed in cubic cells (a spatial hash): the points of cell c are order()[k] for k in
/// range(c) (ascending within a cell), and an open-addressing table finds a cell from its
/// coordinates.
class CellGrid {
 public:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  static constexpr int kBits = 21;  // bits per axis in a packed cell key
  static constexpr std::int64_t kAxisCells = std::int64_t{1} << kBits;

  /// Cells at least `side` wide (wider when the extent would need over 2^21 cells along an axis).
  CellGrid(const std::vector<Vec3>& points, double side);

  std::size_t cells() const { return keys_.size(); }
  double side() const { return side_; }
  /// The points in cell order: position k of the grid holds points[order()[k]].
  const std::vector<Index>& order() const { return order_; }
  /// The positions in order() of the points of cell c.
  std::pair<std::size_t, std::size_t> range(std::size_t c) const { return {start_[c], start_[c + 1]}; }
  /// The points of cell c.
  std::pair<const Index*, const Index*> members(std::size_t c) const {
    return {order_.data() + start_[c], order_.data() + start_[c + 1]};
  }
  /// The cell of every point.
  std::vector<std::uint32_t> cell_of_points() const;
  /// The non-empty cells among the 27 around cell c (itself included), kNone for the others.
  std::array<std::uint32_t, 27> around(std::size_t c) const;
  /// The non-empty cells at most `reach` cells away from cell c along each axis (itself included).
  std::vector<std::uint32_t> within(std::size_t c, int reach) const;
  /// The lowest corner of cell c.
  Vec3 corner(std::size_t c) const;
  /// Cell c's phase in 0..26, from its coordinates modulo 3: two cells of one phase are at least
  /// two cells apart along some axis, so no point of one is within a cell side of a point of the
  /// other.
  int phase(std::size_t c) const;

 private:
  /// Calls f(cell or kNone) for the cells at most `reach` away from cell c along each axis.
  template <typename F>
  void for_each_within(std::size_t c, int reach, const F& f) const;
  std::array<std::int64_t, 3> coordinates(std::size_t c) const;
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const;
  std::uint32_t find(const std::array<std::int64_t, 3>& cell) const;
  static std::uint64_t pack(const std::array<std::int64_t, 3>& c);
  std::size_t hash(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  void build_table();

  Vec3 lo_;
  double side_ = 1;
  std::vector<Index> order_;
  std::vector<std::size_t> start_;
  std::vector<std::uint64_t> keys_;
  /// A slot of the table holds the cell's key beside it, so a look-up reads one place.
  struct Slot {
    std::uint64_t key;
    std::uint32_t cell;
  };
  std::vector<Slot> table_;
  int shift_ = 60;
  std::size_t mask_ = 15;
};

/// values[order[k]] at position k, gathered in parallel: per-point data in a grid's order.
template <typename T>
std::vector<T> in_grid_order(const std::vector<T>& values, const std::vector<Index>& order) {
  std::vector<T> out(order.size());
  tbb::parallel_for(std::size_t{0}, order.size(), [&](std::size_t k) { out[k] = values[order[k]]; });
  return out;
}

}  // namespace medax::services::poisson_detail
