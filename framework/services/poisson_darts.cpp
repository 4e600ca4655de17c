#include "poisson_darts.hpp"

#include "poisson_grid.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>

namespace medax::services::poisson_detail {

namespace {

/// The darts kept so far in the cells around one cell, coordinates apart (one vectorised
/// distance loop per point), with their grid positions for the normal test.
class KeptAround {
 public:
  void gather(const CellGrid& grid, const std::array<std::uint32_t, 27>& around, const std::vector<Vec3>& at,
              const std::vector<char>& kept) {
    x_.clear(), y_.clear(), z_.clear(), position_.clear();
    for (std::uint32_t cell : around) {
      if (cell == CellGrid::kNone) continue;
      const auto [begin, end] = grid.range(cell);
      for (std::size_t k = begin; k < end; ++k)
        if (kept[k]) add(at, k);
    }
  }
  void add(const std::vector<Vec3>& at, std::size_t k) {
    x_.push_back(at[k].x()), y_.push_back(at[k].y()), z_.push_back(at[k].z());
    position_.push_back(static_cast<Index>(k));
  }
  /// Whether no gathered dart with a normal agreeing with normal[k] lies closer than sqrt(r2) to
  /// at[k]. The last added first: the darts of k's own cell, the likeliest to be that close, are
  /// added after the gathered ones, so most candidates that fail do so within a few tests.
  bool free(const std::vector<Vec3>& at, const std::vector<Vec3>& normal, std::size_t k, double r2,
            const NormalRule& rule) const {
    const double qx = at[k].x(), qy = at[k].y(), qz = at[k].z();
    for (std::size_t i = x_.size(); i-- > 0;) {
      const double dx = qx - x_[i], dy = qy - y_[i], dz = qz - z_[i];
      if (dx * dx + dy * dy + dz * dz < r2 && rule.agree(normal[k], normal[position_[i]])) return false;
    }
    return true;
  }

 private:
  std::vector<double> x_, y_, z_;
  std::vector<Index> position_;
};

}  // namespace

/// The grid, the points and normals in its order, and its cells by phase.
struct DartThrower::Grid {
  CellGrid cells;
  std::vector<Vec3> at, normal;
  std::array<std::vector<std::uint32_t>, 27> phases;
  std::vector<std::array<std::uint32_t, 27>> around;
};

DartThrower::DartThrower(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, double side)
    : grid_(new Grid{CellGrid(points, side), {}, {}, {}, {}}) {
  Grid& g = *grid_;
  g.at = in_grid_order(points, g.cells.order());
  g.normal = in_grid_order(normals, g.cells.order());
  g.around.resize(g.cells.cells());
  tbb::parallel_for(std::size_t{0}, g.cells.cells(), [&](std::size_t c) { g.around[c] = g.cells.around(c); });
  for (std::size_t c = 0; c < g.cells.cells(); ++c) g.phases[g.cells.phase(c)].push_back(static_cast<std::uint32_t>(c));
}

DartThrower::~DartThrower() = default;

std::vector<Index> DartThrower::kept(double radius, const NormalRule& rule) const {
  const Grid& g = *grid_;
  if (!(radius <= g.cells.side())) throw std::logic_error("dart throwing: radius wider than the grid's cells");
  // kept[k] for grid position k. A cell writes its own flags and reads those of its 27 cells,
  // none of which is in its phase: the cells of a phase never touch the same flags.
  std::vector<char> kept(g.at.size(), 0);
  const double r2 = radius * radius;
  for (const std::vector<std::uint32_t>& phase : g.phases)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, phase.size()), [&](const tbb::blocked_range<std::size_t>& r) {
      KeptAround darts;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const std::uint32_t c = phase[i];
        darts.gather(g.cells, g.around[c], g.at, kept);
        const auto [begin, end] = g.cells.range(c);
        for (std::size_t k = begin; k < end; ++k)
          if (darts.free(g.at, g.normal, k, r2, rule)) kept[k] = 1, darts.add(g.at, k);
      }
    });
  std::vector<Index> out;
  for (std::size_t k = 0; k < kept.size(); ++k)
    if (kept[k]) out.push_back(g.cells.order()[k]);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace medax::services::poisson_detail
