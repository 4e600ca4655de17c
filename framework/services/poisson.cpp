// Poisson-disk sampling: weighted sample elimination (Yuksel 2015) and dart throwing, both over
// dense uniform candidates.
#include <medax/services/poisson.hpp>

#include <medax/services/kdtree.hpp>
#include <medax/services/sampling.hpp>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace medax::services {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxCandidates = 5e7;

/// Samples whose normals are closer than the angle repel; zero normals (never produced for
/// faces of positive area) agree with everything.
struct NormalRule {
  double min_dot;
  explicit NormalRule(double angle_deg) : min_dot(std::cos(std::clamp(angle_deg, 0.0, 180.0) * kPi / 180.0)) {}
  bool agree(const Vec3& a, const Vec3& b) const { return min_dot <= -1.0 || a.dot(b) > min_dot; }
};

/// A binary max-heap over candidate weights that can lower a weight in place. Ties go to the
/// larger index, so the order is fully determined.
class EliminationHeap {
 public:
  explicit EliminationHeap(const std::vector<double>& weights) : weight_(weights), position_(weights.size()) {
    heap_.resize(weights.size());
    for (std::size_t i = 0; i < heap_.size(); ++i) heap_[i] = static_cast<Index>(i), position_[i] = i;
    for (std::size_t i = heap_.size() / 2; i-- > 0;) sift_down(i);
  }
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  Index pop() {
    const Index top = heap_.front();
    move(heap_.size() - 1, 0);
    heap_.pop_back();
    if (!heap_.empty()) sift_down(0);
    position_[top] = kRemoved;
    return top;
  }
  bool contains(Index i) const { return position_[i] != kRemoved; }
  void decrease(Index i, double by) {
    weight_[i] -= by;
    sift_down(position_[i]);
  }

 private:
  static constexpr std::size_t kRemoved = std::numeric_limits<std::size_t>::max();
  bool above(Index a, Index b) const { return weight_[a] > weight_[b] || (weight_[a] == weight_[b] && a > b); }
  void move(std::size_t from, std::size_t to) {
    heap_[to] = heap_[from];
    position_[heap_[to]] = to;
  }
  void sift_down(std::size_t i) {
    const Index item = heap_[i];
    for (;;) {
      std::size_t child = 2 * i + 1;
      if (child >= heap_.size()) break;
      if (child + 1 < heap_.size() && above(heap_[child + 1], heap_[child])) ++child;
      if (!above(heap_[child], item)) break;
      move(child, i);
      i = child;
    }
    heap_[i] = item;
    position_[item] = i;
  }
  std::vector<double> weight_;
  std::vector<std::size_t> position_;
  std::vector<Index> heap_;
};

/// Area of each sample: its Voronoi cell among its neighbours (with agreeing normals) in its
/// tangent plane, clipped to a disk of radius `bound` (where the surface folds away, as at a thin
/// edge, no neighbour closes the cell), then all scaled so that they sum to `total`.
std::vector<double> tangent_voronoi_areas(const OrientedSamples& samples, double total, double bound,
                                          const NormalRule& rule) {
  const PointIndex index(samples.points);
  const std::size_t k = std::min<std::size_t>(16, samples.size());
  std::vector<double> areas(samples.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<Eigen::Vector2d> polygon, clipped;
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Vec3& n = samples.normals[i];
      const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
      const Vec3 u = n.cross(helper).normalized(), v = n.cross(u);
      polygon.clear();
      for (int a = 0; a < 16; ++a)
        polygon.emplace_back(bound * std::cos(a * kPi / 8), bound * std::sin(a * kPi / 8));
      for (const auto& [j, d] : index.k_nearest(samples.points[i], k)) {
        if (j == i || !rule.agree(n, samples.normals[j])) continue;
        const Vec3 q = samples.points[j] - samples.points[i];
        const Eigen::Vector2d w(q.dot(u), q.dot(v));
        const double c = 0.5 * w.squaredNorm();
        if (!(c > 0)) continue;
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
      }
      double twice = 0;
      for (std::size_t a = 0; a < polygon.size(); ++a) {
        const Eigen::Vector2d& p0 = polygon[a];
        const Eigen::Vector2d& p1 = polygon[(a + 1) % polygon.size()];
        twice += p0.x() * p1.y() - p1.x() * p0.y();
      }
      areas[i] = polygon.size() < 3 ? 0.0 : 0.5 * std::abs(twice);
    }
  });
  double sum = 0;
  for (double a : areas) sum += a;
  if (!(sum > 0)) {
    areas.assign(samples.size(), total / static_cast<double>(samples.size()));
    return areas;
  }
  for (double& a : areas) a *= total / sum;
  return areas;
}

OrientedSamples select(const OrientedSamples& candidates, const std::vector<Index>& chosen) {
  OrientedSamples out;
  out.points.reserve(chosen.size());
  out.normals.reserve(chosen.size());
  for (Index i : chosen) {
    out.points.push_back(candidates.points[i]);
    out.normals.push_back(candidates.normals[i]);
  }
  return out;
}

double checked_area(const SurfaceMesh& mesh) {
  const double area = surface_area(mesh);
  if (!(area > 0) || !std::isfinite(area)) throw std::invalid_argument("cannot sample a mesh with zero area");
  return area;
}

}  // namespace

double poisson_packing_distance(double area, std::size_t count) {
  return 2.0 * std::sqrt(area / (2.0 * std::sqrt(3.0) * static_cast<double>(count)));
}

OrientedSamples sample_poisson_count(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng,
                                     const PoissonDiskOptions& options) {
  if (count == 0) throw std::invalid_argument("Poisson-disk sampling needs a sample count of at least 1");
  const double area = checked_area(mesh);
  const double m = std::ceil(std::max(1.0, options.oversampling) * static_cast<double>(count));
  if (m > kMaxCandidates)
    throw std::invalid_argument("Poisson-disk sampling of " + std::to_string(count) +
                                " samples needs too many candidates; lower the count or the oversampling");
  const OrientedSamples candidates = sample_uniform(mesh, static_cast<std::size_t>(m), rng);
  const std::size_t n_candidates = candidates.size();
  const NormalRule rule(options.normal_angle_deg);

  // Yuksel 2015, §3-4, constants for 2D domains (surfaces): alpha = 8, beta = 0.65, gamma = 1.5.
  const double r_max = poisson_packing_distance(area, count);  // 2·r_max of the paper
  const double r_min = r_max * 0.65 * (1.0 - std::pow(static_cast<double>(count) / static_cast<double>(n_candidates), 1.5));
  const auto weight = [&](double d) { return std::pow(1.0 - std::max(d, r_min) / r_max, 8.0); };

  const PointIndex index(candidates.points);
  std::vector<std::vector<std::pair<Index, double>>> neighbours(n_candidates);
  std::vector<double> weights(n_candidates, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_candidates, 1024), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      auto& list = neighbours[i];
      for (const auto& [j, d] : index.within(candidates.points[i], r_max)) {
        if (j == i || d >= r_max || !rule.agree(candidates.normals[i], candidates.normals[j])) continue;
        const double w = weight(d);
        list.emplace_back(j, w);
        weights[i] += w;
      }
    }
  });

  EliminationHeap heap(weights);
  while (heap.size() > count) {
    const Index removed = heap.pop();
    for (const auto& [j, w] : neighbours[removed])
      if (heap.contains(j)) heap.decrease(j, w);
  }
  std::vector<Index> kept;
  kept.reserve(count);
  for (std::size_t i = 0; i < n_candidates; ++i)
    if (heap.contains(static_cast<Index>(i))) kept.push_back(static_cast<Index>(i));
  OrientedSamples out = select(candidates, kept);
  out.areas = tangent_voronoi_areas(out, area, 0.75 * r_max, rule);
  return out;
}

OrientedSamples sample_poisson_radius(const SurfaceMesh& mesh, double radius, std::mt19937_64& rng,
                                      const PoissonDiskOptions& options) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw std::invalid_argument("Poisson-disk sampling needs a radius > 0");
  const double area = checked_area(mesh);
  // Samples of a hexagonal packing at this spacing: an upper bound of what dart throwing gets.
  const double packing = 2.0 * area / (std::sqrt(3.0) * radius * radius);
  const double m = std::ceil(std::max(1.0, options.oversampling) * std::max(1.0, packing));
  if (m > kMaxCandidates)
    throw std::invalid_argument("Poisson-disk radius " + std::to_string(radius) +
                                " is too small for this surface (it needs over 50 million candidates); "
                                "use a larger radius");
  const OrientedSamples candidates = sample_uniform(mesh, static_cast<std::size_t>(m), rng);
  const NormalRule rule(options.normal_angle_deg);

  // Dart throwing on a hash grid of cell size `radius`: a candidate is kept when no kept sample
  // with an agreeing normal lies closer than the radius (the candidates come in random order).
  struct CellHash {
    std::size_t operator()(const std::array<long long, 3>& c) const {
      return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<long long, 3>, std::vector<Index>, CellHash> grid;
  const auto cell_of = [radius](const Vec3& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() / radius)),
                                    static_cast<long long>(std::floor(p.y() / radius)),
                                    static_cast<long long>(std::floor(p.z() / radius))};
  };
  std::vector<Index> kept;
  const double r2 = radius * radius;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Vec3& p = candidates.points[i];
    const auto c = cell_of(p);
    bool free = true;
    for (long long dx = -1; dx <= 1 && free; ++dx)
      for (long long dy = -1; dy <= 1 && free; ++dy)
        for (long long dz = -1; dz <= 1 && free; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (Index s : it->second)
            if ((candidates.points[s] - p).squaredNorm() < r2 && rule.agree(candidates.normals[s], candidates.normals[i])) {
              free = false;
              break;
            }
        }
    if (!free) continue;
    kept.push_back(static_cast<Index>(i));
    grid[c].push_back(static_cast<Index>(i));
  }
  OrientedSamples out = select(candidates, kept);
  out.areas = tangent_voronoi_areas(out, area, 0.75 * radius / 0.7, rule);
  return out;
}

double min_sample_distance(const OrientedSamples& samples, double normal_angle_deg) {
  double best = std::numeric_limits<double>::infinity();
  if (samples.size() < 2) return best;
  const NormalRule rule(normal_angle_deg);
  const PointIndex index(samples.points);
  const std::size_t k = std::min<std::size_t>(32, samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto near = index.k_nearest(samples.points[i], k);
    bool found = false;
    for (const auto& [j, d] : near)
      if (j != i && rule.agree(samples.normals[i], samples.normals[j])) {
        best = std::min(best, d);  // the nearest agreeing sample: the list is sorted
        found = true;
        break;
      }
    if (found || near.size() == samples.size()) continue;
    // The nearest agreeing sample lies beyond the k nearest.
    if (std::isfinite(best)) {
      for (const auto& [j, d] : index.within(samples.points[i], best))
        if (j != i && rule.agree(samples.normals[i], samples.normals[j])) best = std::min(best, d);
    } else {
      for (std::size_t j = 0; j < samples.size(); ++j)
        if (j != i && rule.agree(samples.normals[i], samples.normals[j]))
          best = std::min(best, (samples.points[i] - samples.points[j]).norm());
    }
  }
  return best;
}

}  // namespace medax::services
