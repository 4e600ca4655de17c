#pragma once
// Neighbour lists and dart throwing over Poisson-disk candidates, through a spatial hash grid
// (private to poisson.cpp). Millions of fixed-radius queries over points that lie on a surface: a grid of
// cells as large as the radius answers each from 27 cells, and all candidates of a cell share
// those 27 look-ups.
#include <medax/geometry.hpp>

#include <functional>
#include <vector>

namespace medax::services::poisson_detail {

/// Compressed rows: the neighbours of point i are index[offset[i] .. offset[i + 1]), closest
/// first (ties by index), each with a value computed from its distance.
struct NeighbourLists {
  std::vector<std::size_t> offset;
  std::vector<Index> index;
  std::vector<double> value;
};

/// For every point, the other points closer than `radius` for which `related(i, j)` holds,
/// closest first, each with value `weigh(distance)`. Deterministic: the same lists whatever the
/// number of threads.
NeighbourLists neighbours_within(const std::vector<Vec3>& points, double radius,
                                 const std::function<bool(Index, Index)>& related,
                                 const std::function<double(double)>& weigh);

/// Dart throwing: goes through the points in index order and keeps each one that is no closer
/// than `radius` to any point kept before it for which `related(i, j)` holds. Returns the kept
/// indices, ascending.
std::vector<Index> dart_throwing(const std::vector<Vec3>& points, double radius,
                                 const std::function<bool(Index, Index)>& related);

}  // namespace medax::services::poisson_detail
