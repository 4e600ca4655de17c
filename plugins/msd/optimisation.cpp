#include "optimisation.hpp"

#include "uncovered_regions.hpp"

#include <medax/context.hpp>

#include <nlopt.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

namespace medax::msd {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Energy of a rejected trial: worse than any accepted one (E_cov ≥ −1, the other terms small).
constexpr double kRejectedEnergy = 1e3;

Energy rejected(std::string why) {
  Energy e;
  e.total = kRejectedEnergy;
  e.rejected = true;
  e.rejection = std::move(why);
  return e;
}

/// Element geometry as a cache key: kind and the exact corner coordinates.
using ElementKey = std::array<double, 10>;
ElementKey key_of(const SkeletonElement& element) {
  ElementKey key{};
  key[0] = static_cast<double>(element.kind);
  for (int c = 0; c < element.corner_count(); ++c)
    for (int k = 0; k < 3; ++k) key[1 + 3 * c + k] = element.corners[c][k];
  return key;
}

/// Why a site set is refused before construction, or empty.
std::string refusal(const MedialMesh& medial, const std::vector<Vec3>& sites, const OptimisationOptions& options,
                    double scale) {
  const double min_distance = options.min_site_distance * scale;
  for (std::size_t i = 0; i < sites.size(); ++i)
    for (std::size_t j = i + 1; j < sites.size(); ++j)
      if ((sites[i] - sites[j]).norm() < min_distance) return "two sites closer than min_site_distance";
  if (options.projection == Projection::FacetCentroid) {
    std::set<Index> facets;
    for (const Vec3& s : sites)
      if (!facets.insert(medial.closest_point(s).facet).second) return "two sites on one facet of M";
  }
  return {};
}

}  // namespace

OptimisationOptions resolve_delta(const OptimisationOptions& options, const TargetMesh& target) {
  OptimisationOptions resolved = options;
  if (options.delta_rule == DeltaRule::MeanEdgeLength)
    resolved.coverage.delta = target.mean_edge_length() / target.scale();
  return resolved;
}

FitOptions search_fit_options(const OptimisationOptions& options) {
  FitOptions fit = options.fit;
  fit.smoothness = options.search_smoothness;
  fit.templates.sphere_vertices = options.search_sphere_vertices;
  return fit;
}

std::vector<SkeletonElement> skeleton_elements(const Skeleton& skeleton) {
  std::vector<SkeletonElement> elements;
  const auto& v = skeleton.vertices;
  for (Index i = 0; i < v.size(); ++i) elements.push_back({ElementKind::Vertex, {i, 0, 0}, {v[i], v[i], v[i]}});
  for (const Segment& e : skeleton.edges)
    elements.push_back({ElementKind::Edge, {e[0], e[1], 0}, {v[e[0]], v[e[1]], v[e[1]]}});
  for (const Tri& t : skeleton.triangles)
    elements.push_back({ElementKind::Triangle, {t[0], t[1], t[2]}, {v[t[0]], v[t[1]], v[t[2]]}});
  return elements;
}

std::vector<Vec3> project_sites(const MedialMesh& medial, const std::vector<Vec3>& points, Projection projection) {
  std::vector<Vec3> sites;
  sites.reserve(points.size());
  for (const Vec3& p : points) {
    const MeshPoint hit = medial.closest_point(p);
    if (projection == Projection::ClosestPoint) {
      sites.push_back(hit.point);
      continue;
    }
    Vec3 centroid = Vec3::Zero();
    const std::vector<Index> corners = medial.facet_vertices(hit.facet);
    for (Index c : corners) centroid += medial.points()[c];
    sites.push_back(centroid / static_cast<double>(corners.size()));
  }
  return sites;
}

double centroid_energy(const std::vector<Vec3>& sites, const std::vector<RvdPiece>& pieces) {
  const std::vector<Vec3> centroids = cell_centroids(pieces, sites.size());
  double energy = 0;
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (centroids[i].allFinite()) energy += (sites[i] - centroids[i]).squaredNorm();  // NaN: a cell without pieces
  return energy;
}

struct EnergyEvaluator::Cache {
  struct Entry {
    Primitive primitive;
    std::vector<Index> covered;   ///< S's vertices the primitive covers, once `has_coverage`
    bool has_coverage = false;
    int last_used = 0;
  };
  std::map<ElementKey, Entry> entries;
  int evaluation = 0;
};

EnergyEvaluator::EnergyEvaluator(const TargetMesh& target, const MedialMesh& medial, const SurfaceCrossing& crossing,
                                 const OptimisationOptions& options)
    : target_(target), medial_(medial), crossing_(crossing), options_(options), cache_(std::make_unique<Cache>()) {}

EnergyEvaluator::~EnergyEvaluator() = default;

std::vector<Primitive> EnergyEvaluator::fit(const std::vector<SkeletonElement>& elements, std::size_t& fitted) {
  const int now = ++cache_->evaluation;
  std::vector<SkeletonElement> missing;
  std::vector<ElementKey> missing_keys;
  for (const SkeletonElement& element : elements) {
    const ElementKey key = key_of(element);
    if (cache_->entries.count(key) || std::find(missing_keys.begin(), missing_keys.end(), key) != missing_keys.end())
      continue;
    missing.push_back(element);
    missing_keys.push_back(key);
  }
  std::vector<Primitive> fresh = fit_primitives(target_, missing, search_fit_options(options_));
  for (std::size_t i = 0; i < fresh.size(); ++i) cache_->entries[missing_keys[i]] = {std::move(fresh[i]), {}, false, now};
  fitted = missing.size();
  std::vector<Primitive> primitives;
  primitives.reserve(elements.size());
  for (const SkeletonElement& element : elements) {
    Cache::Entry& entry = cache_->entries.at(key_of(element));
    entry.last_used = now;
    primitives.push_back(entry.primitive);
    primitives.back().element.ids = element.ids;  // same geometry, this skeleton's numbering
  }
  return primitives;
}

std::vector<std::vector<Index>> EnergyEvaluator::covered_lists(const std::vector<SkeletonElement>& elements) {
  std::vector<Cache::Entry*> missing;
  for (const SkeletonElement& element : elements) {
    Cache::Entry& entry = cache_->entries.at(key_of(element));
    if (!entry.has_coverage && std::find(missing.begin(), missing.end(), &entry) == missing.end())
      missing.push_back(&entry);
  }
  tbb::parallel_for(std::size_t{0}, missing.size(), [&](std::size_t i) {
    missing[i]->covered = covered_vertices(target_, missing[i]->primitive, options_.coverage);
    missing[i]->has_coverage = true;
  });
  std::vector<std::vector<Index>> lists;
  lists.reserve(elements.size());
  for (const SkeletonElement& element : elements) lists.push_back(cache_->entries.at(key_of(element)).covered);
  return lists;
}

void EnergyEvaluator::trim_cache(const Diagram& keep) {
  std::set<ElementKey> kept;
  for (const SkeletonElement& element : keep.elements) kept.insert(key_of(element));
  for (auto it = cache_->entries.begin(); it != cache_->entries.end();) {
    const bool recent = it->second.last_used >= cache_->evaluation - 1;
    it = (recent || kept.count(it->first)) ? std::next(it) : cache_->entries.erase(it);
  }
}

Diagram EnergyEvaluator::evaluate(const std::vector<Vec3>& frozen, const std::vector<Vec3>& free, IterationLog* log) {
  IterationLog local;
  IterationLog& times = log ? *log : local;
  Diagram diagram;
  auto start = Clock::now();
  diagram.sites = frozen;
  const std::vector<Vec3> projected = project_sites(medial_, free, options_.projection);
  diagram.sites.insert(diagram.sites.end(), projected.begin(), projected.end());
  std::string why = refusal(medial_, diagram.sites, options_, target_.scale());
  times.seconds_projection = seconds_since(start);
  times.sites = diagram.sites.size();
  if (!why.empty()) {
    diagram.energy = rejected(std::move(why));
    return diagram;
  }
  start = Clock::now();
  try {
    diagram.skeleton = construct_skeleton(medial_, diagram.sites, crossing_, options_.construction);
  } catch (const std::invalid_argument& e) {
    diagram.energy = rejected(std::string("construction: ") + e.what());
    return diagram;
  }
  times.seconds_construction = seconds_since(start);
  start = Clock::now();
  diagram.elements = skeleton_elements(diagram.skeleton);
  diagram.primitives = fit(diagram.elements, times.fitted);
  times.seconds_fitting = seconds_since(start);
  start = Clock::now();
  diagram.coverage = union_coverage(target_, covered_lists(diagram.elements));
  Energy& e = diagram.energy;
  e.coverage = diagram.coverage.energy;
  const double unit = target_.scale();
  e.centroid = centroid_energy(diagram.sites, diagram.skeleton.pieces) / (unit * unit);
  e.count = static_cast<double>(diagram.skeleton.vertices.size() - diagram.sites.size());
  e.total = e.coverage + options_.centroid_weight * e.centroid + options_.count_weight * e.count;
  times.seconds_energy = seconds_since(start);
  return diagram;
}

namespace {

bool fully_covered(const Coverage& coverage) {
  return !coverage.covered.empty() &&
         std::all_of(coverage.covered.begin(), coverage.covered.end(), [](char c) { return c != 0; });
}

/// Which tets have their centroid inside some fitted primitive.
std::vector<char> covered_tets(const SolidTets& tets, const std::vector<Primitive>& primitives) {
  std::vector<PrimitiveShape> shapes;
  for (const Primitive& p : primitives)
    if (p.fitted) shapes.emplace_back(p);
  std::vector<char> covered(tets.size(), 0);
  tbb::parallel_for(std::size_t{0}, tets.size(), [&](std::size_t t) {
    for (const PrimitiveShape& shape : shapes)
      if (shape.near(tets.centroids[t], 0) && shape.radial(tets.centroids[t]) < 0) {
        covered[t] = 1;
        return;
      }
  });
  return covered;
}

/// The state of the schedule across rounds.
class Schedule {
 public:
  Schedule(const TargetMesh& target, const MedialMesh& medial, const OptimisationOptions& options,
           const std::function<void(const IterationLog&)>& on_iteration, const std::function<bool()>& cancelled)
      : target_(target), medial_(medial), options_(resolve_delta(options, target)), crossing_(target.mesh()),
        evaluator_(target, medial, crossing_, options_), on_iteration_(on_iteration), cancelled_(cancelled) {}

  OptimisationResult run();

 private:
  double objective(const std::vector<double>& x);
  void run_round(std::vector<Vec3>& free, int budget);
  std::vector<Vec3> new_sites();
  OptimisationResult finish(std::string reason);
  bool out_of_budget() const { return iteration_ >= options_.max_iterations; }

  const TargetMesh& target_;
  const MedialMesh& medial_;
  const OptimisationOptions options_;
  SurfaceCrossing crossing_;
  EnergyEvaluator evaluator_;
  const std::function<void(const IterationLog&)>& on_iteration_;
  const std::function<bool()>& cancelled_;
  OptimisationResult result_;
  SolidTets tets_;
  std::vector<Vec3> frozen_;
  bool have_best_ = false;
  int iteration_ = 0;
  int round_ = 0;
  // Within a round: evaluations since the round's best last decreased, and the simplex size.
  int since_decrease_ = 0;
  int round_evaluations_ = 0;
  int simplex_size_ = 0;
  double round_best_ = std::numeric_limits<double>::infinity();
  bool stop_round_ = false;
  bool user_cancelled_ = false;
};

std::vector<Vec3> to_points(const std::vector<double>& x) {
  std::vector<Vec3> points(x.size() / 3);
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  return points;
}

double Schedule::objective(const std::vector<double>& x) {
  if (cancelled_ && cancelled_()) {
    user_cancelled_ = stop_round_ = true;
    return kRejectedEnergy;
  }
  IterationLog log;
  Diagram diagram = evaluator_.evaluate(frozen_, to_points(x), &log);
  log.iteration = ++iteration_;
  log.round = round_;
  log.energy = diagram.energy;
  ++round_evaluations_;
  const double e = diagram.energy.total;
  if (e < round_best_) {
    round_best_ = e;
    since_decrease_ = 0;
  } else {
    ++since_decrease_;
  }
  if (!diagram.energy.rejected && (!have_best_ || e < result_.best.energy.total)) {
    result_.best = std::move(diagram);
    have_best_ = true;
  }
  evaluator_.trim_cache(result_.best);
  log.best = have_best_ ? result_.best.energy.total : e;
  result_.log.push_back(log);
  if (on_iteration_) on_iteration_(log);
  // The stall rule counts only after the initial simplex (its dim + 1 points are not NM steps).
  const bool stalled = round_evaluations_ > simplex_size_ && since_decrease_ >= options_.stall;
  if (stalled || out_of_budget() || (have_best_ && fully_covered(result_.best.coverage))) stop_round_ = true;
  return e;
}

void Schedule::run_round(std::vector<Vec3>& free, int budget) {
  const unsigned dim = static_cast<unsigned>(3 * free.size());
  nlopt::opt opt(nlopt::LN_NELDERMEAD, dim);
  std::vector<double> lower(dim), upper(dim), x(dim);
  Vec3 lo = target_.mesh().vertices.front(), hi = lo;
  for (const Vec3& v : target_.mesh().vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  for (unsigned i = 0; i < dim; ++i) {
    lower[i] = lo[i % 3];
    upper[i] = hi[i % 3];
    x[i] = std::clamp(free[i / 3][i % 3], lower[i], upper[i]);
  }
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_maxeval(std::max(1, std::min(budget, options_.max_iterations - iteration_)));
  opt.set_xtol_abs(options_.xtol * target_.scale());
  round_evaluations_ = since_decrease_ = 0;
  simplex_size_ = static_cast<int>(dim) + 1;
  round_best_ = std::numeric_limits<double>::infinity();
  stop_round_ = false;
  auto f = [](const std::vector<double>& v, std::vector<double>&, void* self) {
    auto* schedule = static_cast<Schedule*>(self);
    const double e = schedule->objective(v);
    if (schedule->stop_round_) throw nlopt::forced_stop();
    return e;
  };
  opt.set_min_objective(f, this);
  double value = 0;
  try {
    opt.optimize(x, value);
  } catch (const nlopt::forced_stop&) {
  } catch (const nlopt::roundoff_limited&) {
  }
  if (user_cancelled_) throw Cancelled();
}

std::vector<Vec3> Schedule::new_sites() {
  if (tets_.size() == 0) {  // S is tetrahedralised once, when the first round leaves gaps
    const auto start = Clock::now();
    tets_ = tetrahedralize_solid(target_.mesh(), options_.tetgen_switches);
    result_.seconds_tetrahedralisation = seconds_since(start);
    result_.tets = tets_.size();
  }
  const auto start = Clock::now();
  const std::vector<UncoveredRegion> regions =
      uncovered_regions(tets_, covered_tets(tets_, result_.best.primitives));
  RoundLog& round = result_.additions.emplace_back();
  round.uncovered_regions = regions.size();
  if (!regions.empty()) round.largest_region_volume = regions.front().volume;
  const double min_distance = options_.min_site_distance * target_.scale();
  std::vector<Vec3> sites, taken = frozen_;
  for (const UncoveredRegion& region : regions) {
    if (sites.size() == options_.add_count) break;
    const Vec3 site = project_sites(medial_, {region.centre}, options_.projection).front();
    const bool clear = std::all_of(taken.begin(), taken.end(),
                                   [&](const Vec3& s) { return (s - site).norm() >= min_distance; });
    if (!clear) continue;  // the region's centre projects next to a site: try the next region
    sites.push_back(site);
    taken.push_back(site);
  }
  round.sites_added = sites.size();
  round.seconds = seconds_since(start);
  return sites;
}

OptimisationResult Schedule::finish(std::string reason) {
  // The best diagram refitted with the final options; its coverage and E_cov follow.
  const auto start = Clock::now();
  Diagram& best = result_.best;
  best.primitives = fit_primitives(target_, best.elements, options_.fit);
  best.coverage = coverage(target_, best.primitives, options_.coverage);
  best.energy.total += best.coverage.energy - best.energy.coverage;
  best.energy.coverage = best.coverage.energy;
  result_.seconds_final_fit = seconds_since(start);
  result_.stop_reason = std::move(reason);
  return std::move(result_);
}

OptimisationResult Schedule::run() {
  result_.delta = options_.coverage.delta;
  std::vector<Vec3> free;
  for (Index v : farthest_point_sites(medial_, options_.initial_sites, static_cast<Index>(options_.start_vertex)))
    free.push_back(medial_.points()[v]);
  int budget = options_.first_iterations;
  double previous_best = std::numeric_limits<double>::infinity();
  for (;; ++round_, budget = options_.add_every) {
    run_round(free, std::min(budget, static_cast<int>(9 * free.size())));
    result_.rounds = round_ + 1;
    if (!have_best_)
      throw std::runtime_error("every trial site set was rejected (" + result_.log.back().energy.rejection +
                               "); lower `min_site_distance` or give a finer medial mesh");
    if (fully_covered(result_.best.coverage)) return finish("full coverage");
    if (out_of_budget()) return finish("max_iterations reached");
    if (!(result_.best.energy.total < previous_best)) return finish("a round brought no decrease");
    previous_best = result_.best.energy.total;
    frozen_ = result_.best.sites;
    free = new_sites();
    if (free.empty()) return finish("no uncovered region left to add a site in");
  }
}

}  // namespace

OptimisationResult optimise(const TargetMesh& target, const MedialMesh& medial, const OptimisationOptions& options,
                            const std::function<void(const IterationLog&)>& on_iteration,
                            const std::function<bool()>& cancelled) {
  Schedule schedule(target, medial, options, on_iteration, cancelled);
  return schedule.run();
}

}  // namespace medax::msd
