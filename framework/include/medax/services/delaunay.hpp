#pragma once
// Delaunay tetrahedralization of surface points (CGAL, parallel with TBB), returned as plain
// arrays so callers never include CGAL.
#include <medax/geometry.hpp>

#include <vector>

namespace medax::services {

struct DelaunayTetrahedralization {
  /// Distinct input points actually used (duplicates merged): point index per vertex.
  std::vector<Index> vertex_point;
  /// For every input point, its Delaunay vertex.
  std::vector<Index> point_vertex;
  /// Finite tetrahedra, as indices of input points (positively oriented).
  std::vector<std::array<Index, 4>> cells;
  /// neighbours[c][k]: the cell across the facet opposite corner k; kInfinite when that
  /// neighbour is an infinite cell (the facet is on the convex hull).
  std::vector<std::array<std::int64_t, 4>> neighbours;
  /// Circumcentre and circumradius of every finite cell (the Voronoi vertices).
  std::vector<Vec3> circumcentres;
  std::vector<double> circumradii;

  static constexpr std::int64_t kInfinite = -1;
};

struct DelaunayOptions {
  bool parallel = true;  ///< TBB parallel insertion and circumcentres (same result, faster)
};

/// Throws std::invalid_argument when the points span less than three dimensions.
DelaunayTetrahedralization delaunay_tetrahedralize(const std::vector<Vec3>& points,
                                                   const DelaunayOptions& options = {});

}  // namespace medax::services
