#pragma once
// The areas of Poisson-disk samples (private to the Poisson-disk sampling).
#include "poisson_neighbours.hpp"

#include <medax/surface.hpp>

#include <vector>

namespace medax::services::poisson_detail {

/// Area of each sample: its Voronoi cell among its 15 nearest other samples (those with
/// agreeing normals) in its tangent plane, clipped to a disk of radius `bound` (where the
/// surface folds away, as at a thin edge, no neighbour closes the cell), then all scaled so that
/// they sum to `total`. The nearest samples are those of a k-d tree search, found through a grid
/// of cells `cell_spacings` times the packing distance of the samples wide where that gives the
/// same list (see poisson_areas.cpp); the areas do not depend on it.
std::vector<double> tangent_voronoi_areas(const OrientedSamples& samples, double total, double bound,
                                          const NormalRule& rule, double cell_spacings = 2.5);

}  // namespace medax::services::poisson_detail
