// Poisson-disk sampling: weighted sample elimination (Yuksel 2015) and dart throwing, both over
// dense uniform candidates.
#include <medax/services/poisson.hpp>

#include <medax/services/sampling.hpp>

#include "poisson_areas.hpp"
#include "poisson_darts.hpp"
#include "poisson_grid.hpp"
#include "poisson_neighbours.hpp"
#include "poisson_queue.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace medax::services {

namespace {

constexpr double kMaxCandidates = 5e7;

using poisson_detail::NormalRule;

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

/// Asks the cache for the neighbour row of candidate i. The pops jump around in memory, and
/// fetching each removal's row is most of the elimination's time: the row of the queue's likely
/// next pop is fetched while the current removal's neighbours are lowered.
void prefetch_row(const poisson_detail::NeighbourGraph& near, Index i) {
  const std::size_t first = near.offset[i], last = near.offset[i + 1];
  if (first == last) return;
  constexpr std::size_t kLine = 64;
  for (std::size_t k = first; k < last; k += kLine / sizeof(Index)) __builtin_prefetch(&near.index[k]);
  for (std::size_t k = first; k < last; k += kLine / sizeof(double)) __builtin_prefetch(&near.value[k]);
  __builtin_prefetch(&near.index[last - 1]);
  __builtin_prefetch(&near.value[last - 1]);
}

/// Reports progress when asked to (PoissonDiskOptions::progress).
void report(const PoissonDiskOptions& options, double fraction, std::string_view phase) {
  if (options.progress) options.progress(fraction, phase);
}

/// Removals (or darts) between two progress reports.
constexpr std::size_t kRemovalsPerReport = std::size_t{1} << 16;

/// Weighted sample elimination over the graph (its sums are taken as the initial weights): the
/// candidate with the most crowded neighbourhood goes first, until `count` remain (sequential:
/// each removal lowers its neighbours' weights). Calls `done(fraction)` every
/// kRemovalsPerReport removals. Returns the kept candidates, ascending.
std::vector<Index> eliminate(poisson_detail::NeighbourGraph near, std::size_t count,
                             const std::function<void(double)>& done) {
  poisson_detail::EliminationQueue queue(std::move(near.sum), near.original);
  const double removals = static_cast<double>(queue.size() - std::min(count, queue.size()));
  for (std::size_t pops = 1; queue.size() > count; ++pops) {
    if (pops % kRemovalsPerReport == 0) done(static_cast<double>(pops) / removals);
    const Index removed = queue.pop();
    const Index next = queue.likely_next();
    __builtin_prefetch(&near.offset[next]);
    for (std::size_t k = near.offset[removed]; k < near.offset[removed + 1]; ++k)
      queue.decrease(near.index[k], near.value[k]);
    prefetch_row(near, next);
  }
  std::vector<Index> kept;
  kept.reserve(count);
  for (std::size_t i = 0; i < near.original.size(); ++i)
    if (queue.contains(static_cast<Index>(i))) kept.push_back(near.original[i]);
  std::sort(kept.begin(), kept.end());
  return kept;
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

namespace {

/// Runs `f` with at most `max_threads` TBB threads when that is positive.
template <typename F>
auto with_threads(int max_threads, const F& f) {
  if (max_threads <= 0) return f();
  tbb::task_arena arena(max_threads);
  return arena.execute(f);
}

/// The candidates thinned by dart throwing (PoissonCandidates::Darts) at kDartSpacing packing
/// spacings, the minimum distance the samples then keep. A maximal set there would hold about
/// 1.4 × count samples on a flat surface (a maximal Poisson-disk set covers 0.55-0.6 of the
/// plane against the packing's 0.91); five uniform candidates per sample are too few to reach
/// it and give 1.02 × on koala.
/// Where fewer than count are kept (curved or creased surfaces, fewer candidates), the radius
/// shrinks by the square root of the shortfall (a maximal set's size goes as 1 / radius²), and a
/// little more, until enough are; the elimination then removes the few extra.
OrientedSamples thin_by_darts(const OrientedSamples& candidates, std::size_t count, double spacing,
                              const NormalRule& rule) {
  constexpr double kDartSpacing = 0.65, kMargin = 0.98;
  const double widest = kDartSpacing * spacing;
  // Cells four radii wide: dozens of candidates in each, against 27 look-ups per cell.
  const poisson_detail::DartThrower darts(candidates.points, candidates.normals, 4 * widest);
  for (double radius = widest;;) {
    const std::vector<Index> kept = darts.kept(radius, rule);
    if (kept.size() >= count) return select(candidates, kept);
    if (kept.size() * 2 > candidates.size()) return candidates;  // nearly all kept: thinning does not pay
    radius *= kMargin * std::sqrt(static_cast<double>(kept.size()) / static_cast<double>(count));
  }
}

/// Exactly `count` of the candidates by weighted sample elimination, with their areas.
OrientedSamples eliminate_to(const OrientedSamples& candidates, std::size_t count, double area, const NormalRule& rule,
                             const PoissonDiskOptions& options) {
  // Yuksel 2015, §3-4, constants for 2D domains (surfaces): alpha = 8, beta = 0.65, gamma = 1.5.
  const double r_max = poisson_packing_distance(area, count);  // 2·r_max of the paper
  const double r_min =
      r_max * 0.65 * (1.0 - std::pow(static_cast<double>(count) / static_cast<double>(candidates.size()), 1.5));
  const poisson_detail::EliminationWeight weight(r_min, r_max);

  // Each candidate's weight is the sum over its neighbours closer than r_max (closest first); the
  // graph is freed once the elimination has run.
  poisson_detail::NeighbourGraph near =
      poisson_detail::neighbours_within(candidates.points, candidates.normals, r_max, rule, weight);
  report(options, 0.4, "neighbour lists");
  OrientedSamples out = select(candidates, eliminate(std::move(near), count, [&](double fraction) {
                                 report(options, 0.4 + 0.45 * fraction, "elimination");
                               }));
  report(options, 0.85, "elimination");
  out.areas = poisson_detail::tangent_voronoi_areas(out, area, 0.75 * r_max, rule);
  report(options, 1.0, "areas");
  return out;
}

OrientedSamples poisson_by_count(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng,
                                 const PoissonDiskOptions& options) {
  if (count == 0) throw std::invalid_argument("Poisson-disk sampling needs a sample count of at least 1");
  const double area = checked_area(mesh);
  const double m = std::ceil(std::max(1.0, options.oversampling) * static_cast<double>(count));
  if (m > kMaxCandidates)
    throw std::invalid_argument("Poisson-disk sampling of " + std::to_string(count) +
                                " samples needs too many candidates; lower the count or the oversampling");
  const OrientedSamples uniform = sample_uniform(mesh, static_cast<std::size_t>(m), rng);
  report(options, 0.1, "candidates");
  const NormalRule rule(options.normal_angle_deg);
  if (options.candidates == PoissonCandidates::Uniform) return eliminate_to(uniform, count, area, rule, options);
  const OrientedSamples darts = thin_by_darts(uniform, count, poisson_packing_distance(area, count), rule);
  report(options, 0.2, "dart throwing");
  return eliminate_to(darts, count, area, rule, options);
}

OrientedSamples poisson_by_radius(const SurfaceMesh& mesh, double radius, std::mt19937_64& rng,
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
  report(options, 0.1, "candidates");
  const NormalRule rule(options.normal_angle_deg);

  // Dart throwing: a candidate is kept when no kept sample with an agreeing normal lies closer
  // than the radius (the candidates come in random order).
  const std::vector<Index> kept = poisson_detail::dart_throwing(
      candidates.points, radius,
      [&](Index i, Index j) { return rule.agree(candidates.normals[i], candidates.normals[j]); },
      kRemovalsPerReport, [&](double fraction) { report(options, 0.1 + 0.7 * fraction, "dart throwing"); });
  OrientedSamples out = select(candidates, kept);
  report(options, 0.8, "dart throwing");
  out.areas = poisson_detail::tangent_voronoi_areas(out, area, 0.75 * radius / 0.7, rule);
  report(options, 1.0, "areas");
  return out;
}

}  // namespace

OrientedSamples sample_poisson_count(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng,
                                     const PoissonDiskOptions& options) {
  return with_threads(options.max_threads, [&] { return poisson_by_count(mesh, count, rng, options); });
}

OrientedSamples sample_poisson_radius(const SurfaceMesh& mesh, double radius, std::mt19937_64& rng,
                                      const PoissonDiskOptions& options) {
  return with_threads(options.max_threads, [&] { return poisson_by_radius(mesh, radius, rng, options); });
}

namespace {

/// The distance from sample i to its nearest other sample with an agreeing normal (infinity when
/// there is none), by brute force.
double nearest_agreeing(const OrientedSamples& samples, const NormalRule& rule, std::size_t i) {
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < samples.size(); ++j)
    if (j != i && rule.agree(samples.normals[i], samples.normals[j]))
      best2 = std::min(best2, (samples.points[i] - samples.points[j]).squaredNorm());
  return std::sqrt(best2);
}

/// The smallest distance between two samples with agreeing normals, if it is at most `side`
/// (otherwise any value above `side`): every such pair lies in two neighbouring cells of a grid
/// that wide, so only those are compared, cell by cell in parallel (the minimum is the same
/// whatever the split).
double closest_pair_within(const OrientedSamples& samples, const NormalRule& rule, double side) {
  const poisson_detail::CellGrid grid(samples.points, side);
  const std::vector<Vec3> at = poisson_detail::in_grid_order(samples.points, grid.order());
  const std::vector<Vec3> normal = poisson_detail::in_grid_order(samples.normals, grid.order());
  const double none = std::numeric_limits<double>::infinity();
  const double best2 = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, grid.cells()), none,
      [&](const tbb::blocked_range<std::size_t>& cells, double best) {
        for (std::size_t c = cells.begin(); c != cells.end(); ++c) {
          const auto [begin, end] = grid.range(c);
          for (const std::uint32_t other : grid.around(c)) {
            if (other == poisson_detail::CellGrid::kNone) continue;
            const auto [first, last] = grid.range(other);
            for (std::size_t k = begin; k < end; ++k)
              for (std::size_t j = first; j < last; ++j)
                if (j != k && rule.agree(normal[k], normal[j])) best = std::min(best, (at[k] - at[j]).squaredNorm());
          }
        }
        return best;
      },
      [](double a, double b) { return std::min(a, b); });
  return std::sqrt(best2);
}

}  // namespace

double min_sample_distance(const OrientedSamples& samples, double normal_angle_deg) {
  const double none = std::numeric_limits<double>::infinity();
  if (samples.size() < 2) return none;
  const NormalRule rule(normal_angle_deg);
  // A few samples' nearest distances bound the answer from above: a grid that wide, or wider,
  // then finds it. Cells four bounds wide (about three spacings on blue noise) hold a dozen
  // samples: fewer cells to look up against more pairs to compare, the fastest trade measured
  // (1M koala samples, 2 threads: 0.40-0.48 s; two bounds 0.59-0.61 s, one 1.0 s).
  constexpr std::size_t kProbes = 16;
  constexpr double kCellsPerBound = 4;
  double bound = none;
  for (std::size_t p = 0; p < kProbes; ++p)
    bound = std::min(bound, nearest_agreeing(samples, rule, p * samples.size() / kProbes));
  if (bound == 0) return 0;  // a probe has a partner at its very position
  if (std::isfinite(bound)) return closest_pair_within(samples, rule, kCellsPerBound * bound);
  // No probe has a partner: widen the grid until a pair shows or it spans all samples.
  Vec3 lo = samples.points.front(), hi = lo;
  for (const Vec3& p : samples.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double extent = (hi - lo).maxCoeff();
  for (double side = extent > 0 ? extent / std::cbrt(static_cast<double>(samples.size())) : 1.0;; side *= 2) {
    const double best = closest_pair_within(samples, rule, side);
    if (best <= side || !(side < extent)) return best;  // (a NaN extent ends it too)
  }
}

}  // namespace medax::services
