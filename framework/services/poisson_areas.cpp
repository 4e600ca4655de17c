// Tangent Voronoi areas of Poisson-disk samples. Each area clips a polygon by the bisectors of
// the sample's 16 nearest samples (itself included) in the order of a k-d tree search (nanoflann),
// so the rounding depends on that list and its order. A grid finds the same list faster: the
// candidates in the 27 cells around a sample (125 where those do not suffice), sorted by squared
// distance (computed as nanoflann does), are the k-d tree's answer when the 16th is closer than
// anything outside those cells and no two of the first 17 distances are equal (with a tie, the
// k-d tree's order depends on its traversal). The few samples where the grid cannot vouch for its
// list go through the k-d tree (built only then).
#include "poisson_areas.hpp"

#include "poisson_grid.hpp"

#include <medax/services/kdtree.hpp>
#include <medax/services/poisson.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

namespace medax::services::poisson_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kNearest = 16;

using Polygon = std::vector<Eigen::Vector2d>;

/// The 16-gon inscribed in the disk of radius `bound`, where every cell starts.
Polygon disk(double bound) {
  Polygon polygon;
  for (int a = 0; a < 16; ++a) polygon.emplace_back(bound * std::cos(a * kPi / 8), bound * std::sin(a * kPi / 8));
  return polygon;
}

/// The squared distance from the origin (the sample) to the polygon's farthest vertex.
double farthest_vertex2(const Polygon& polygon) {
  double farthest = 0;
  for (const Eigen::Vector2d& p : polygon) farthest = std::max(farthest, p.squaredNorm());
  return farthest;
}

/// The area of the tangent Voronoi cell of points[i] among points[near[..]] (closest first;
/// i itself is skipped), `polygon` and `clipped` being scratch space.
double cell_area(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, std::size_t i,
                 const std::vector<std::size_t>& near, const NormalRule& rule, const Polygon& start, Polygon& polygon,
                 Polygon& clipped) {
  const Vec3& n = normals[i];
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = n.cross(helper).normalized(), v = n.cross(u);
  polygon = start;
  double reach2 = farthest_vertex2(polygon);
  for (std::size_t j : near) {
    if (j == i || !rule.agree(n, normals[j])) continue;
    const Vec3 q = points[j] - points[i];
    const Eigen::Vector2d w(q.dot(u), q.dot(v));
    const double c = 0.5 * w.squaredNorm();
    if (!(c > 0)) continue;
    // A bisector at least twice the farthest vertex away (with a margin far above the rounding)
    // leaves every vertex strictly inside: the clip would copy the polygon as it is.
    if (c > 2 * reach2 * (1 + 1e-9)) continue;
    // Keep the half-plane x·w ≤ |w|²/2 (the side of sample i).
    clipped.clear();
    for (std::size_t a = 0; a < polygon.size(); ++a) {
      const Eigen::Vector2d& p0 = polygon[a];
      const Eigen::Vector2d& p1 = polygon[(a + 1) % polygon.size()];
      const double s0 = p0.dot(w) - c, s1 = p1.dot(w) - c;
      if (s0 <= 0) clipped.push_back(p0);
      if ((s0 < 0) != (s1 < 0) && s0 != s1) clipped.push_back(p0 + (s0 / (s0 - s1)) * (p1 - p0));
    }
    polygon.swap(clipped);
    if (polygon.size() < 3) break;
    reach2 = farthest_vertex2(polygon);
  }
  double twice = 0;
  for (std::size_t a = 0; a < polygon.size(); ++a) {
    const Eigen::Vector2d& p0 = polygon[a];
    const Eigen::Vector2d& p1 = polygon[(a + 1) % polygon.size()];
    twice += p0.x() * p1.y() - p1.x() * p0.y();
  }
  return polygon.size() < 3 ? 0.0 : 0.5 * std::abs(twice);
}

/// A sample near another: squared distance and grid position.
struct Near {
  double d2;
  std::size_t k;
  bool operator<(const Near& o) const { return d2 < o.d2; }
};

/// The cells at most `reach` cells from a cell along each axis, in which a search can vouch for
/// the nearest samples closer than `reach` cells from the sample.
struct Block {
  int reach;
  std::vector<std::uint32_t> cells;
};

/// The k nearest of the grid's point at position `k` (cell c), closest first, as grid
/// positions in `out`; false when the cells of `block` cannot vouch for the k-d tree's list.
bool grid_nearest(const CellGrid& grid, const std::vector<Vec3>& at, std::size_t c, std::size_t k, std::size_t count,
                  const Block& block, std::vector<Near>& near, std::vector<std::size_t>& out) {
  const Vec3& q = at[k];
  // Distance from q to the outside of the block of cells, less a margin for the rounding of the
  // cell assignment: the list is vouched for when its last is closer than that.
  const Vec3 low = grid.corner(c) - Vec3::Constant(block.reach * grid.side());
  const Vec3 high = low + Vec3::Constant((2 * block.reach + 1) * grid.side());
  const double clearance = std::min((q - low).minCoeff(), (high - q).minCoeff()) - 1e-9 * grid.side();
  if (!(clearance > 0)) return false;
  // Only points possibly closer than the clearance can make a vouched list (a superset of
  // them, by a relative margin far above the rounding of the squares): with fewer than `count`
  // of them the list cannot be vouched for, and a point left out cannot tie with its last.
  const double kept_below = clearance * clearance * (1 + 1e-9);
  near.clear();
  for (std::uint32_t cell : block.cells) {
    const auto [begin, end] = grid.range(cell);
    for (std::size_t j = begin; j < end; ++j) {
      const double dx = q.x() - at[j].x(), dy = q.y() - at[j].y(), dz = q.z() - at[j].z();
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < kept_below) near.push_back({d2, j});
    }
  }
  if (near.size() < count) return false;
  const auto sorted = static_cast<std::ptrdiff_t>(std::min(near.size(), count + 1));
  std::nth_element(near.begin(), near.begin() + sorted - 1, near.end());
  std::sort(near.begin(), near.begin() + sorted);
  for (std::ptrdiff_t a = 1; a < sorted; ++a)
    if (near[a].d2 == near[a - 1].d2) return false;
  if (!(std::sqrt(near[count - 1].d2) < clearance)) return false;
  out.clear();
  for (std::size_t a = 0; a < count; ++a) out.push_back(near[a].k);
  return true;
}

/// The unscaled cell areas, through the grid; the samples the grid cannot vouch for are listed
/// in `left` (ascending).
std::vector<double> grid_cell_areas(const OrientedSamples& samples, double cell_side, double bound,
                                    const NormalRule& rule, std::vector<Index>& left) {
  const std::size_t count = std::min(kNearest, samples.size());
  const CellGrid grid(samples.points, cell_side);
  const std::vector<Vec3> at = in_grid_order(samples.points, grid.order());
  const std::vector<Vec3> normal = in_grid_order(samples.normals, grid.order());
  const Polygon start = disk(bound);
  std::vector<double> areas(samples.size(), 0.0);
  std::mutex left_mutex;
  tbb::parallel_for(std::size_t{0}, grid.cells(), [&](std::size_t c) {
    const Block around{1, grid.within(c, 1)};
    Block wider{2, {}};
    std::vector<Near> near;
    std::vector<std::size_t> nearest;
    Polygon polygon, clipped;
    std::vector<Index> missed;
    const auto [begin, end] = grid.range(c);
    for (std::size_t k = begin; k < end; ++k) {
      // Where the 27 cells around cannot vouch for the list (a sample far from the others), the
      // 125 cells around may.
      bool found = grid_nearest(grid, at, c, k, count, around, near, nearest);
      if (!found && wider.cells.empty()) wider.cells = grid.within(c, wider.reach);
      if (!found) found = grid_nearest(grid, at, c, k, count, wider, near, nearest);
      if (found)
        areas[grid.order()[k]] = cell_area(at, normal, k, nearest, rule, start, polygon, clipped);
      else
        missed.push_back(grid.order()[k]);
    }
    if (missed.empty()) return;
    const std::lock_guard<std::mutex> lock(left_mutex);
    left.insert(left.end(), missed.begin(), missed.end());
  });
  std::sort(left.begin(), left.end());
  return areas;
}

}  // namespace

std::vector<double> tangent_voronoi_areas(const OrientedSamples& samples, double total, double bound,
                                          const NormalRule& rule, double cell_spacings) {
  if (samples.empty()) return {};
  // By default cells 2.5 spacings wide: the 16 nearest of a blue-noise sample lie within about 2.1.
  const double spacing = poisson_packing_distance(total, samples.size());
  std::vector<Index> left;
  std::vector<double> areas = grid_cell_areas(samples, cell_spacings * spacing, bound, rule, left);
  if (!left.empty()) {
    const PointIndex index(samples.points);
    const std::size_t count = std::min(kNearest, samples.size());
    const Polygon start = disk(bound);
    tbb::parallel_for(std::size_t{0}, left.size(), [&](std::size_t a) {
      Polygon polygon, clipped;
      std::vector<std::size_t> nearest;
      for (const auto& [j, d] : index.k_nearest(samples.points[left[a]], count)) nearest.push_back(j);
      areas[left[a]] = cell_area(samples.points, samples.normals, left[a], nearest, rule, start, polygon, clipped);
    });
  }
  double sum = 0;
  for (double a : areas) sum += a;
  if (!(sum > 0)) {
    areas.assign(samples.size(), total / static_cast<double>(samples.size()));
    return areas;
  }
  for (double& a : areas) a *= total / sum;
  return areas;
}

}  // namespace medax::services::poisson_detail
