#pragma once
// Neighbour lists and dart throwing over Poisson-disk candidates, through a spatial hash grid
// (private to the Poisson-disk sampling). Millions of fixed-radius queries over points that lie on
// a surface: a grid of cells as large as the radius answers each from 27 cells, and all points of
// a cell share those 27 look-ups.
#include <medax/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

namespace medax::services::poisson_detail {

/// Samples whose normals are closer than the angle repel; zero normals (never produced for
/// faces of positive area) agree with everything.
struct NormalRule {
  double min_dot;
  explicit NormalRule(double angle_deg)
      : min_dot(std::cos(std::clamp(angle_deg, 0.0, 180.0) * 3.14159265358979323846 / 180.0)) {}
  bool agree(const Vec3& a, const Vec3& b) const { return min_dot <= -1.0 || a.dot(b) > min_dot; }
};

/// Yuksel's weight of a neighbour at distance d: (1 - max(d, r_min) / r_max)^8. The weight of
/// all neighbours closer than r_min is computed once (about a third of them).
struct EliminationWeight {
  double r_min, r_max, at_r_min;
  EliminationWeight(double r_min_, double r_max_)
      : r_min(r_min_), r_max(r_max_), at_r_min(std::pow(1.0 - r_min_ / r_max_, 8.0)) {}
  double operator()(double d) const { return d <= r_min ? at_r_min : std::pow(1.0 - d / r_max, 8.0); }
};

/// The neighbour graph of the candidates, renumbered along a Morton curve of grid cells so that
/// neighbours are close in memory: internal point k is candidate original[k] (within a cell in
/// ascending candidate order). Compressed rows: the neighbours of k are index[offset[k] ..
/// offset[k + 1]) (internal numbers), closest first with ties by candidate index, each with its
/// weight in `value`; sum[k] adds up the row's values in that order.
struct NeighbourGraph {
  std::vector<Index> original;
  std::vector<std::size_t> offset;
  // Not zeroed before the rows are written, in parallel: at a million samples they hold 90
  // million entries (1 GB), which zeroing took one thread through page by page.
  std::unique_ptr<Index[]> index;
  std::unique_ptr<double[]> value;
  std::vector<double> sum;
};

/// For every point, the other points closer than `radius` whose normals agree by `rule`, each
/// with value `weigh(distance)`. Deterministic: the same graph whatever the number of threads.
NeighbourGraph neighbours_within(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, double radius,
                                 const NormalRule& rule, const EliminationWeight& weigh);

/// Dart throwing: goes through the points in index order and keeps each one that is no closer
/// than `radius` to any point kept before it for which `related(i, j)` holds (in batches of
/// `every` points, most tests in parallel, the same points); calls `done(fraction)` after each
/// batch. `related` is called from several threads. Returns the kept indices, ascending.
std::vector<Index> dart_throwing(const std::vector<Vec3>& points, double radius,
                                 const std::function<bool(Index, Index)>& related, std::size_t every,
                                 const std::function<void(double)>& done);

}  // namespace medax::services::poisson_detail
