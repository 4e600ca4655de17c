#include "poisson_grid.hpp"

#include <medax/services/morton.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>

namespace medax::services::poisson_detail {

CellGrid::CellGrid(const std::vector<Vec3>& points, double side) {
  if (points.empty()) {
    start_.push_back(0);
    build_table();
    return;
  }
  lo_ = points.front();
  Vec3 hi = lo_;
  for (const Vec3& p : points) lo_ = lo_.cwiseMin(p), hi = hi.cwiseMax(p);
  side_ = std::max(side, (hi - lo_).maxCoeff() / static_cast<double>(kAxisCells - 2));
  // Sorted by (Morton code, index): neighbouring cells are mostly close in the order.
  std::vector<std::pair<std::uint64_t, Index>> morton(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    const auto c = cell_of(points[i]);
    morton[i] = {morton_code(c[0], c[1], c[2]), static_cast<Index>(i)};
  });
  stable_sort_by_code(morton);
  order_.resize(points.size());
  for (std::size_t k = 0; k < morton.size(); ++k) {
    order_[k] = morton[k].second;
    if (k == 0 || morton[k].first != morton[k - 1].first) {
      start_.push_back(k);
      keys_.push_back(pack(cell_of(points[order_[k]])));
    }
  }
  start_.push_back(order_.size());
  build_table();
}

std::vector<std::uint32_t> CellGrid::cell_of_points() const {
  std::vector<std::uint32_t> cell(order_.size());
  tbb::parallel_for(std::size_t{0}, cells(), [&](std::size_t c) {
    for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) cell[order_[k]] = static_cast<std::uint32_t>(c);
  });
  return cell;
}

template <typename F>
void CellGrid::for_each_within(std::size_t c, int reach, const F& f) const {
  const auto centre = coordinates(c);
  for (std::int64_t dx = -reach; dx <= reach; ++dx)
    for (std::int64_t dy = -reach; dy <= reach; ++dy)
      for (std::int64_t dz = -reach; dz <= reach; ++dz) f(find({centre[0] + dx, centre[1] + dy, centre[2] + dz}));
}

std::array<std::uint32_t, 27> CellGrid::around(std::size_t c) const {
  std::array<std::uint32_t, 27> out;
  int n = 0;
  for_each_within(c, 1, [&](std::uint32_t cell) { out[n++] = cell; });
  return out;
}

std::vector<std::uint32_t> CellGrid::within(std::size_t c, int reach) const {
  std::vector<std::uint32_t> out;
  for_each_within(c, reach, [&](std::uint32_t cell) {
    if (cell != kNone) out.push_back(cell);
  });
  return out;
}

Vec3 CellGrid::corner(std::size_t c) const {
  const auto at = coordinates(c);
  return lo_ + side_ * Vec3(static_cast<double>(at[0]), static_cast<double>(at[1]), static_cast<double>(at[2]));
}

int CellGrid::phase(std::size_t c) const {
  const auto at = coordinates(c);
  return static_cast<int>(9 * (at[0] % 3) + 3 * (at[1] % 3) + at[2] % 3);
}

std::array<std::int64_t, 3> CellGrid::coordinates(std::size_t c) const {
  const std::uint64_t k = keys_[c], mask = kAxisCells - 1;
  return {static_cast<std::int64_t>(k >> (2 * kBits)), static_cast<std::int64_t>((k >> kBits) & mask),
          static_cast<std::int64_t>(k & mask)};
}

std::array<std::int64_t, 3> CellGrid::cell_of(const Vec3& p) const {
  return {static_cast<std::int64_t>((p.x() - lo_.x()) / side_), static_cast<std::int64_t>((p.y() - lo_.y()) / side_),
          static_cast<std::int64_t>((p.z() - lo_.z()) / side_)};
}

std::uint32_t CellGrid::find(const std::array<std::int64_t, 3>& cell) const {
  for (std::int64_t x : cell)
    if (x < 0 || x >= kAxisCells) return kNone;
  const std::uint64_t key = pack(cell);
  for (std::size_t slot = hash(key);; slot = (slot + 1) & mask_) {
    const Slot& at = table_[slot];
    if (at.cell == kNone || at.key == key) return at.cell;
  }
}

std::uint64_t CellGrid::pack(const std::array<std::int64_t, 3>& c) {
  return (static_cast<std::uint64_t>(c[0]) << (2 * kBits)) | (static_cast<std::uint64_t>(c[1]) << kBits) |
         static_cast<std::uint64_t>(c[2]);
}

void CellGrid::build_table() {
  int bits = 4;
  while ((std::size_t{1} << bits) < 2 * keys_.size()) ++bits;
  shift_ = 64 - bits;
  mask_ = (std::size_t{1} << bits) - 1;
  table_.assign(std::size_t{1} << bits, Slot{0, kNone});
  for (std::size_t c = 0; c < keys_.size(); ++c) {
    std::size_t slot = hash(keys_[c]);
    while (table_[slot].cell != kNone) slot = (slot + 1) & mask_;
    table_[slot] = {keys_[c], static_cast<std::uint32_t>(c)};
  }
}

}  // namespace medax::services::poisson_detail
