#include "vmas.hpp"

#include "energy.hpp"
#include "split.hpp"

#include <medax/params.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace medax::vmas {

namespace {
/// Adds the wall time of its scope to a counter.
class Timer {
 public:
  explicit Timer(double& sink) : sink_(sink), start_(std::chrono::steady_clock::now()) {}
  ~Timer() { sink_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  Timer(const Timer&) = delete;
  Timer& operator=(const Timer&) = delete;

 private:
  double& sink_;
  std::chrono::steady_clock::time_point start_;
};
}  // namespace

VmasSolver::VmasSolver(std::shared_ptr<const VmasInput> input, VmasOptions options)
    : input_(std::move(input)), options_(options) {
  if (!input_) throw std::invalid_argument("no input");
  if (input_->vertex_balls.empty())
    throw std::invalid_argument("the input was prepared without shrinking balls (InputOptions)");
  if (options_.min_cluster_size < 1) options_.min_cluster_size = 1;
  if (options_.partition_sqem == PartitionSqem::VertexNormal) normal_quadrics_ = vertex_normal_quadrics(*input_);
  push(initial_sphere());
  cluster_of_.assign(input_->size(), -1);
}

Sphere VmasSolver::initial_sphere() const {
  const VmasInput& in = *input_;
  if (options_.initial_sphere == InitialSphere::BoxCorner) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    for (Index v = 0; v < in.size(); ++v)
      if (in.active(v)) lo = lo.cwiseMin(in.points[v]);
    if (!lo.allFinite()) throw std::runtime_error("the input has no vertex used by a face or sample");
    return {lo, in.scale};
  }
  // The largest shrinking ball (the authors' code; notes §2.8).
  Index best = 0;
  double best_r = -1;
  for (Index v = 0; v < in.size(); ++v)
    if (in.active(v) && in.vertex_balls[v].radius > best_r) best_r = in.vertex_balls[v].radius, best = v;
  if (!(best_r > 0)) throw std::runtime_error("no shrinking ball could be computed on this input");
  return in.vertex_balls[best];
}

SphereId VmasSolver::push(const Sphere& s) {
  spheres_.push_back(s);
  ids_.push_back(next_id_);
  moved_.push_back(1);
  regrouped_.push_back(1);
  settled_.push_back(0);
  return next_id_++;
}

void VmasSolver::set_sphere(std::size_t i, const Sphere& s) {
  const Sphere& old = spheres_[i];
  if (s.centre != old.centre || s.radius != old.radius) moved_[i] = 1;
  spheres_[i] = s;
}

void VmasSolver::erase_sphere(std::size_t i) {
  const auto at = [i](auto& v) { v.erase(v.begin() + static_cast<std::ptrdiff_t>(i)); };
  at(spheres_), at(ids_), at(moved_), at(regrouped_), at(settled_);
  const int gone = static_cast<int>(i);
  for (int& c : cluster_of_)
    if (c == gone) c = -1;  // searched afresh at the next partition
    else if (c > gone) --c;
}

std::size_t VmasSolver::partition() {
  const std::vector<int> before = cluster_of_;
  reassign_vertices(*input_, spheres_, options_.lambda_partition, moved_, cluster_of_, &partition_quadrics());
  std::fill(moved_.begin(), moved_.end(), 0);
  for (std::size_t v = 0; v < cluster_of_.size(); ++v)
    if (before[v] != cluster_of_[v]) {
      if (before[v] >= 0) regrouped_[static_cast<std::size_t>(before[v])] = 1;
      if (cluster_of_[v] >= 0) regrouped_[static_cast<std::size_t>(cluster_of_[v])] = 1;
    }
  clusters_ = group_clusters(cluster_of_, spheres_.size());
  // Spheres with a too-small cluster are deleted; their vertices stay unassigned for this
  // iteration (the authors' code; notes §2.3). Never delete them all.
  const auto small = [&](std::size_t i) { return clusters_.size(i) < options_.min_cluster_size; };
  std::size_t culled = 0;
  for (std::size_t i = 0; i < spheres_.size(); ++i) culled += small(i);
  if (culled == 0 || culled == spheres_.size()) return 0;
  for (std::size_t i = spheres_.size(); i-- > 0;)  // from the back: clusters_ stays indexed as before
    if (small(i)) erase_sphere(i);
  clusters_ = group_clusters(cluster_of_, spheres_.size());
  return culled;
}

void VmasSolver::compute_stats() {
  const std::size_t n = clusters_.count();
  stats_.assign(n, ClusterStats{});
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    stats_[i] = cluster_stats(*input_, partition_quadrics(), clusters_.begin(i), clusters_.size(i), spheres_[i],
                              options_.lambda_partition);
  });
}

const std::vector<PackedQuadric>& VmasSolver::partition_quadrics() const {
  return options_.partition_sqem == PartitionSqem::VertexNormal ? normal_quadrics_ : input_->quadrics;
}

void VmasSolver::correct_all() {
  std::vector<Sphere> corrected(spheres_.size());
  tbb::parallel_for(std::size_t{0}, spheres_.size(), [&](std::size_t i) { corrected[i] = input_->correct(spheres_[i]); });
  for (std::size_t i = 0; i < spheres_.size(); ++i) set_sphere(i, corrected[i]);
}

void VmasSolver::update_spheres() {
  const VmasInput& in = *input_;
  UpdateOptions uo;
  uo.lambda = options_.lambda_update;
  uo.rows = options_.sqem_rows;
  uo.steps = options_.gn_steps;
  uo.max_iterations = options_.gn_max_iterations;
  uo.tolerance = options_.gn_tolerance * in.scale;
  // The update of a sphere is a function of its cluster and its start. In the local scope a
  // sphere whose cluster is unchanged and whose last solve converged would only repeat that
  // solve (and its correction), so it keeps its exact value; a split or an edit then costs
  // updates only where clusters change, spreading as far as they keep changing.
  const bool full = options_.update_scope == UpdateScope::Full;
  std::vector<Sphere> updated(spheres_.size());
  std::vector<char> due(spheres_.size(), 0);
  for (std::size_t i = 0; i < spheres_.size(); ++i)
    due[i] = clusters_.size(i) > 0 && (full || regrouped_[i] || !settled_[i]);
  {
    Timer t(times_.update);
    tbb::parallel_for(std::size_t{0}, spheres_.size(), [&](std::size_t i) {
      if (!due[i]) return;
      const UpdateResult r = update_sphere(in, clusters_.begin(i), clusters_.size(i), spheres_[i], uo);
      updated[i] = r.sphere;
      settled_[i] = r.converged;
      regrouped_[i] = 0;
    });
  }
  if (options_.correction == Correction::Always) {
    Timer t(times_.correction);
    tbb::parallel_for(std::size_t{0}, spheres_.size(), [&](std::size_t i) {
      if (due[i]) updated[i] = in.correct(updated[i]);
    });
  }
  for (std::size_t i = 0; i < spheres_.size(); ++i)
    if (due[i]) set_sphere(i, updated[i]);
}

IterationReport VmasSolver::step(bool allow_split) {
  const VmasInput& in = *input_;
  const double s2 = in.scale * in.scale;
  IterationReport rep;
  rep.iteration = ++iteration_;
  {
    Timer t(times_.partition);
    rep.culled = partition();
  }
  {
    Timer t(times_.errors);
    compute_stats();
    for (const ClusterStats& st : stats_) rep.energy_partition += st.energy;
  }

  update_spheres();
  {
    Timer t(times_.errors);
    compute_stats();
    for (const ClusterStats& st : stats_) {
      rep.energy += st.energy;
      rep.total_error += st.error;
      rep.max_error = std::max(rep.max_error, st.error);
    }
  }
  rep.converged = std::abs(rep.total_error - previous_total_) < options_.converge_eps * s2;
  previous_total_ = rep.total_error;
  const bool count_mode = options_.stop_mode == StopMode::Count;
  const bool target_met = count_mode ? spheres_.size() >= options_.target_spheres
                                     : rep.max_error < options_.error_threshold * s2;
  if (spheres_.size() > best_count_) best_count_ = spheres_.size(), last_progress_ = iteration_;
  if (rep.total_error < best_total_ - options_.converge_eps * s2) best_total_ = rep.total_error, last_progress_ = iteration_;
  rep.stalled = options_.stall_iterations > 0 && iteration_ - last_progress_ >= options_.stall_iterations;
  rep.stop = (rep.converged && target_met) || rep.stalled || iteration_ >= options_.max_iterations;

  const int period = std::max(1, options_.split_period);
  if (allow_split && !rep.stop && !target_met && (rep.converged || (iteration_ - 1) % period == 0)) {
    Timer t(times_.splits);
    rep.splits = split_round();
    // The CGoGN code tests the stop after the round: converged and now at the target ends here.
    if (options_.stop_test == StopTest::AfterSplit && count_mode && rep.converged)
      rep.stop = spheres_.size() >= options_.target_spheres;
  }
  rep.spheres = spheres_.size();
  last_ = rep;
  return rep;
}

std::size_t VmasSolver::split_round() {
  const VmasInput& in = *input_;
  if (options_.correction == Correction::OnSplit) {
    correct_all();
    compute_stats();
  }
  SplitRound round;
  round.count_mode = options_.stop_mode == StopMode::Count;
  round.target = options_.target_spheres;
  round.threshold = options_.error_threshold * (in.scale * in.scale);
  round.fraction = options_.split_fraction;
  round.max_per_round = options_.split_max_per_round;
  std::vector<double> errors(stats_.size());
  for (std::size_t i = 0; i < stats_.size(); ++i) errors[i] = stats_[i].error;
  const Adjacency adj = cluster_adjacency(in.graph_edges, cluster_of_, spheres_.size());
  std::size_t splits = 0;
  for (Index i : select_splits(errors, adj, round)) {
    const Sphere& ball = in.vertex_balls[stats_[i].split_vertex];
    if (!(ball.radius > 0)) continue;
    push(ball);
    ++splits;
  }
  return splits;
}

IterationReport VmasSolver::iterate() { return step(true); }
IterationReport VmasSolver::relax() { return step(false); }

IterationReport VmasSolver::run(const std::function<bool(const IterationReport&)>& after_each) {
  IterationReport rep = last_;
  while (iteration_ < options_.max_iterations) {
    rep = iterate();
    if (after_each && !after_each(rep)) break;
    if (rep.stop) break;
  }
  return rep;
}

void VmasSolver::finish() {
  if (options_.correction == Correction::End || options_.correction == Correction::OnSplit) correct_all();
  if (clusters_.count() != spheres_.size()) partition();
  compute_stats();
}

void VmasSolver::refresh_after_edit() {
  Timer t(times_.edits);
  partition();
  compute_stats();
  double total = 0;
  for (const ClusterStats& st : stats_) total += st.error;
  previous_total_ = total;
  // An edit restarts the stall test from the edited state.
  best_total_ = std::numeric_limits<double>::infinity();
  best_count_ = spheres_.size();
  last_progress_ = iteration_;
}

std::size_t VmasSolver::index_of(SphereId id) const {
  const auto it = std::find(ids_.begin(), ids_.end(), id);
  if (it == ids_.end()) throw std::out_of_range("no sphere with id " + std::to_string(id));
  return static_cast<std::size_t>(it - ids_.begin());
}

bool VmasSolver::contains(SphereId id) const { return std::find(ids_.begin(), ids_.end(), id) != ids_.end(); }

SphereId VmasSolver::split_sphere(SphereId id) {
  const std::size_t i = index_of(id);
  Index v;
  if (i < stats_.size() && clusters_.size(i) > 0) {
    v = stats_[i].split_vertex;
  } else {  // not partitioned yet: the vertex nearest to its centre
    v = input_->nearest_vertex(spheres_[i].centre);
  }
  return add_sphere(v);
}

SphereId VmasSolver::add_sphere(Index vertex) {
  if (vertex >= input_->size()) throw std::out_of_range("no input vertex " + std::to_string(vertex));
  const Sphere& ball = input_->vertex_balls[vertex];
  if (!(ball.radius > 0)) throw std::invalid_argument("vertex " + std::to_string(vertex) + " has no shrinking ball");
  const SphereId id = push(ball);
  refresh_after_edit();
  return id;
}

void VmasSolver::remove_sphere(SphereId id) {
  const std::size_t i = index_of(id);
  if (spheres_.size() == 1) throw std::invalid_argument("cannot remove the last sphere");
  erase_sphere(i);
  refresh_after_edit();
}

SphereId VmasSolver::nearest_sphere(const Vec3& p) const {
  const Vec3 local = p - input_->origin;
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    const double d = (spheres_[i].centre - local).squaredNorm();
    if (d < best_d) best_d = d, best = i;
  }
  return ids_.at(best);
}

std::vector<SphereInfo> VmasSolver::spheres() const {
  std::vector<SphereInfo> out(spheres_.size());
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    SphereInfo& s = out[i];
    s.id = ids_[i];
    s.centre = spheres_[i].centre + input_->origin;
    s.radius = spheres_[i].radius;
    if (i < stats_.size()) {
      s.error = stats_[i].error;
      s.area = stats_[i].area;
      s.cluster_size = clusters_.size(i);
      s.split_vertex = stats_[i].split_vertex;
    }
  }
  return out;
}

SphereInfo VmasSolver::sphere(SphereId id) const { return spheres().at(index_of(id)); }

Adjacency VmasSolver::adjacency() const {
  return cluster_adjacency(input_->graph_edges, cluster_of_, spheres_.size());
}

MedialComplex VmasSolver::complex(bool connect, TriangleRule rule) const {
  MedialComplex mc;
  const std::size_t n = spheres_.size();
  for (const Sphere& s : spheres_) mc.add_vertex(s.centre + input_->origin, s.radius);
  mc.generators.resize(n);
  for (std::size_t i = 0; i < n && i < clusters_.count(); ++i)
    mc.generators[i].assign(clusters_.begin(i), clusters_.begin(i) + clusters_.size(i));
  mc.generator_kind = input_->kind == InputKind::Mesh ? "mesh_vertex" : "sample";
  auto& error = mc.add(kVmasError, 0.0);
  auto& area = mc.add(kVmasArea, 0.0);
  auto& id = mc.add(kVmasId, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (i < stats_.size()) error[i] = stats_[i].error, area[i] = stats_[i].area;
    id[i] = static_cast<int>(ids_[i]);
  }
  if (connect) {
    const DualComplex d = dual_complex(adjacency(), rule, input_->triangles, cluster_of_);
    mc.edges = d.edges;
    mc.faces = d.faces;
  }
  return mc;
}

std::string summary(const VmasOptions& o) {
  std::ostringstream out;
  if (o.stop_mode == StopMode::Count)
    out << "target " << o.target_spheres << " spheres";
  else
    out << "error threshold " << o.error_threshold << "·scale²";
  out << ", λ_partition " << o.lambda_partition << ", λ_update " << o.lambda_update << ", update "
      << choice_name(kSqemRows, o.sqem_rows) << ", correction " << choice_name(kCorrections, o.correction);
  return out.str();
}

}  // namespace medax::vmas
