// CGAL Point Set Processing on OrientedSamples: the cloud is copied into (point, normal) pairs,
// processed, and copied back; removals come back as CGAL's partition (kept points first).
#include "point_processing.hpp"

#include <medax/io.hpp>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/grid_simplify_point_set.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/jet_smooth_point_set.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>
#include <CGAL/remove_outliers.h>
#include <CGAL/wlop_simplify_and_regularize_point_set.h>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <vector>

namespace medax::pointset {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointNormal = std::pair<Point, Vector>;
using Cloud = std::vector<PointNormal>;
using Tag = CGAL::Sequential_tag;  // deterministic, and the machine's cores are shared

const auto kMaps = CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointNormal>())
                       .normal_map(CGAL::Second_of_pair_property_map<PointNormal>());

Cloud to_cgal(const OrientedSamples& samples) {
  const bool normals = samples.normals.size() == samples.size();
  Cloud cloud;
  cloud.reserve(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Vec3& p = samples.points[i];
    const Vec3 n = normals ? samples.normals[i] : Vec3::Zero();
    cloud.emplace_back(Point(p.x(), p.y(), p.z()), Vector(n.x(), n.y(), n.z()));
  }
  return cloud;
}

/// The first `count` pairs back into `samples` (normals only when `normals`), areas shared.
void from_cgal(const Cloud& cloud, std::size_t count, bool normals, OrientedSamples& samples) {
  samples.points.clear();
  samples.normals.clear();
  for (std::size_t i = 0; i < count; ++i) {
    const auto& [p, n] = cloud[i];
    samples.points.emplace_back(p.x(), p.y(), p.z());
    if (normals) samples.normals.push_back(Vec3(n.x(), n.y(), n.z()).normalized());
  }
  share_area(samples);
}

double diagonal(const OrientedSamples& cloud) { return bbox_diagonal(cloud.points); }

}  // namespace

void check_cloud(const OrientedSamples& cloud, std::size_t k, const std::string& what) {
  if (cloud.size() < k + 1)
    throw std::invalid_argument(fmt::format("{} with {} neighbours needs at least {} points but the cloud has {}: "
                                            "give a denser cloud or lower `k`",
                                            what, k, k + 1, cloud.size()));
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : cloud.points) mean += p;
  mean /= static_cast<double>(cloud.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : cloud.points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::Vector3d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues();
  if (!(spread.maxCoeff() > 0) || !std::isfinite(spread.maxCoeff()))
    throw std::invalid_argument(fmt::format("the {} points of the cloud coincide; {} needs a surface", cloud.size(),
                                            what));
  const double thinness = std::sqrt(std::max(spread.minCoeff(), 0.0) / spread.maxCoeff());
  if (thinness < 1e-6)
    throw std::invalid_argument(fmt::format("the cloud is flat (its thinnest extent is {:.2g} of its largest): the "
                                            "points of a solid's surface span 3D, these lie on a plane",
                                            thinness));
}

NormalReport estimate_and_orient_normals(OrientedSamples& samples, bool estimate, const NormalOptions& options) {
  check_cloud(samples, options.k, estimate ? "normal estimation" : "normal orientation");
  if (!estimate && samples.normals.size() != samples.size())
    throw std::invalid_argument("the cloud has no normals to orient; estimate them (`estimate: auto`)");
  Cloud cloud = to_cgal(samples);
  const std::vector<Vec3> given = samples.normals;
  const unsigned k = static_cast<unsigned>(options.k);
  if (estimate && options.method == NormalMethod::Jet) CGAL::jet_estimate_normals<Tag>(cloud, k, kMaps);
  if (estimate && options.method == NormalMethod::Pca) CGAL::pca_estimate_normals<Tag>(cloud, k, kMaps);
  NormalReport report;
  report.estimated = estimate;
  std::size_t kept = cloud.size();
  if (options.orient)
    kept = static_cast<std::size_t>(std::distance(cloud.begin(), CGAL::mst_orient_normals(cloud, k, kMaps)));
  report.dropped = cloud.size() - kept;
  if (!estimate && report.dropped == 0)
    for (std::size_t i = 0; i < kept; ++i) {
      const Vector& n = cloud[i].second;
      report.flipped += Vec3(n.x(), n.y(), n.z()).dot(given[i]) < 0;
    }
  from_cgal(cloud, kept, true, samples);
  return report;
}

std::size_t remove_outliers(OrientedSamples& samples, const OutlierOptions& options) {
  check_cloud(samples, options.k, "outlier removal");
  Cloud cloud = to_cgal(samples);
  const double spacing = CGAL::compute_average_spacing<Tag>(cloud, static_cast<unsigned>(options.k), kMaps);
  const auto first_removed = CGAL::remove_outliers<Tag>(
      cloud, static_cast<unsigned>(options.k),
      kMaps.threshold_percent(options.max_percent).threshold_distance(options.distance * spacing));
  const auto kept = static_cast<std::size_t>(std::distance(cloud.begin(), first_removed));
  const std::size_t removed = cloud.size() - kept;
  from_cgal(cloud, kept, samples.normals.size() == samples.size(), samples);
  return removed;
}

void jet_smooth(OrientedSamples& samples, std::size_t k) {
  check_cloud(samples, k, "jet smoothing");
  Cloud cloud = to_cgal(samples);
  CGAL::jet_smooth_point_set<Tag>(cloud, static_cast<unsigned>(k), kMaps);
  from_cgal(cloud, cloud.size(), samples.normals.size() == samples.size(), samples);
}

std::size_t simplify(OrientedSamples& samples, const SimplifyOptions& options) {
  check_cloud(samples, 3, "simplification");
  const std::size_t before = samples.size();
  const double scale = diagonal(samples);
  Cloud cloud = to_cgal(samples);
  if (options.method == SimplifyMethod::Grid) {
    const auto first_removed = CGAL::grid_simplify_point_set(cloud, options.cell * scale, kMaps);
    from_cgal(cloud, static_cast<std::size_t>(std::distance(cloud.begin(), first_removed)),
              samples.normals.size() == samples.size(), samples);
  } else {
    std::vector<Point> points;
    for (const auto& pn : cloud) points.push_back(pn.first);
    std::vector<Point> output;
    std::srand(1);  // WLOP picks its initial points with std::rand: a fixed seed keeps runs identical
    CGAL::wlop_simplify_and_regularize_point_set<Tag>(
        points, std::back_inserter(output),
        CGAL::parameters::select_percentage(options.select_percent).neighbor_radius(options.neighbor_radius * scale));
    Cloud result;
    for (const Point& p : output) result.emplace_back(p, Vector(0, 0, 0));
    from_cgal(result, result.size(), false, samples);
  }
  return before - samples.size();
}

void share_area(OrientedSamples& cloud) {
  const double area = estimate_surface_area(cloud.points);
  cloud.areas.assign(cloud.size(), cloud.size() ? area / static_cast<double>(cloud.size()) : 0.0);
}

}  // namespace medax::pointset
