#pragma once
// Delaunay tetrahedralization of surface points (CGAL), returned as plain arrays so callers never
// include CGAL. From 50k points on, the insertion is concurrent (CGAL's Parallel_tag
// triangulation with a grid of locks, in a biased randomized order whose large rounds go in
// concurrently); below, it is CGAL's sequential range insertion. The per-cell work (ordering,
// neighbours, circumcentres) is parallel in both. The result does not depend on the number of
// threads: below 50k points cells are numbered by their sorted corners' point indices; from 50k
// on by their corners' ranks in the reversed insertion order (a Hilbert curve, so consecutive
// cells are neighbours in space), which depends on the points only. The concurrent path gives
// corners in a canonical order (smallest first, positively oriented), and CGAL breaks cospherical
// ties by a symbolic perturbation that does not depend on the insertion order.
#include <medax/geometry.hpp>

#include <functional>
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
  /// Circumcentre and circumradius of every finite cell (the Voronoi vertices). The centre is
  /// equidistant from the four corners up to its final rounding, also for nearly flat cells
  /// (recomputed with exact rationals); the radius is the distance to corner 0.
  std::vector<Vec3> circumcentres;
  std::vector<double> circumradii;

  static constexpr std::int64_t kInfinite = -1;
};

struct DelaunayOptions {
  bool parallel = true;  ///< TBB-parallel insertion and per-cell work (same result, faster)
  /// When > 0, at most this many threads (a TBB arena of that size); 0: TBB's default.
  int max_threads = 0;
};

/// Throws std::invalid_argument when the points span less than three dimensions.
DelaunayTetrahedralization delaunay_tetrahedralize(const std::vector<Vec3>& points,
                                                   const DelaunayOptions& options = {});

/// The same, while `alongside` (work that does not need the result, e.g. building an inside
/// test) runs on another core when `options.parallel`; otherwise `alongside` runs first. An
/// exception from either is rethrown once both have finished.
DelaunayTetrahedralization delaunay_tetrahedralize_alongside(const std::vector<Vec3>& points,
                                                             const DelaunayOptions& options,
                                                             const std::function<void()>& alongside);

}  // namespace medax::services
