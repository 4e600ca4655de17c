#pragma once
// Dart throwing in parallel over Poisson-disk candidates (private to the Poisson-disk sampling):
// the `darts` thinning that the elimination by count can start from.
#include "poisson_neighbours.hpp"

#include <medax/geometry.hpp>

#include <memory>
#include <vector>

namespace medax::services::poisson_detail {

/// Dart throwing over a fixed set of points, at any radius up to the grid's cell side. A throw
/// keeps a subset of the points none of which is closer than the radius to another with an
/// agreeing normal, and which leaves out no point farther than that from all kept ones (maximal
/// over the points). The grid's cells are taken one phase at a time (CellGrid::phase), the cells
/// of a phase in parallel, the points of a cell in ascending index order, each tested against the
/// points kept before it in its 27 cells: the result depends on the phases, not on the threads.
class DartThrower {
 public:
  /// Cells `side` wide: the largest radius a throw may use. Cells several radii wide hold dozens
  /// of points each, so that the 27 cell look-ups per cell do not outweigh the distance tests.
  DartThrower(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, double side);
  ~DartThrower();
  /// The kept indices, ascending (radius <= side).
  std::vector<Index> kept(double radius, const NormalRule& rule) const;

 private:
  struct Grid;
  std::unique_ptr<Grid> grid_;
};

}  // namespace medax::services::poisson_detail
