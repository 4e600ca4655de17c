#pragma once
// Point-set processing for the `pointset` package: thin wrappers over CGAL's Point Set
// Processing (outlier removal, normal estimation and MST orientation, jet smoothing, grid and
// WLOP simplification) on medax's OrientedSamples. Plain C++ at the interface: CGAL stays in the
// .cpp. Every function is deterministic (sequential CGAL calls on the points in their order).
#include <medax/surface.hpp>

#include <cstddef>
#include <string>

namespace medax::pointset {

/// Checks that a cloud can be processed with k neighbours: at least `k + 1` points, finite, and
/// spanning 3D (its thinnest principal extent above 1e-6 of its largest). Throws
/// std::invalid_argument saying what is wrong and what to do; `what` names the operation.
void check_cloud(const OrientedSamples& cloud, std::size_t k, const std::string& what);

enum class NormalMethod {
  Jet,  ///< CGAL::jet_estimate_normals (a quadric fitted to the k neighbours)
  Pca,  ///< CGAL::pca_estimate_normals (the plane of the k neighbours)
};

struct NormalOptions {
  NormalMethod method = NormalMethod::Jet;
  std::size_t k = 18;  ///< neighbours of the estimate and of the orientation graph
  bool orient = true;  ///< orient the normals consistently (CGAL::mst_orient_normals)
};

struct NormalReport {
  bool estimated = false;    ///< the normals were estimated (else the given ones were oriented)
  std::size_t flipped = 0;   ///< normals the orientation reversed
  std::size_t dropped = 0;   ///< points the orientation could not reach (removed)
};

/// Estimates unoriented normals (when `estimate`), then orients them with a minimum spanning tree
/// of the kNN graph (when options.orient), starting at the highest point whose normal is made to
/// point up (+z), which is outward on a closed surface. Points the tree cannot reach are removed.
NormalReport estimate_and_orient_normals(OrientedSamples& cloud, bool estimate, const NormalOptions& options);

struct OutlierOptions {
  std::size_t k = 24;             ///< neighbours of the root mean squared distance
  double max_percent = 100.0;     ///< at most this share of the points is removed
  double distance = 2.0;          ///< ... and only those whose distance exceeds this × the average spacing
};
/// CGAL::remove_outliers: a point is an outlier when the root mean squared distance to its k
/// nearest neighbours exceeds `distance` × the cloud's average spacing (CGAL::compute_average_spacing:
/// the mean over the points of their mean distance to the same k neighbours; the rule of CGAL's own
/// example). Returns the number of points removed.
std::size_t remove_outliers(OrientedSamples& cloud, const OutlierOptions& options);

/// CGAL::jet_smooth_point_set: each point projected onto the jet (degree 2) fitted to its k
/// neighbours. Normals, when present, are kept.
void jet_smooth(OrientedSamples& cloud, std::size_t k);

enum class SimplifyMethod {
  Grid,  ///< CGAL::grid_simplify_point_set: one point per cell of side `cell` (keeps normals)
  Wlop,  ///< CGAL::wlop_simplify_and_regularize_point_set (new points: normals dropped)
};
struct SimplifyOptions {
  SimplifyMethod method = SimplifyMethod::Grid;
  double cell = 0.01;             ///< grid cell side, × bbox diagonal
  double select_percent = 20.0;   ///< WLOP: share of the points kept
  double neighbor_radius = 0.05;  ///< WLOP: × bbox diagonal
};
/// Returns the number of points removed.
std::size_t simplify(OrientedSamples& cloud, const SimplifyOptions& options);

/// Gives every sample an equal share of the estimated surface area (medax::estimate_surface_area).
void share_area(OrientedSamples& cloud);

}  // namespace medax::pointset
