// The Q-MAT collapse loop (notes §1.4–1.6, §2.6): optimal sphere per edge, priority (E + k)·γ²,
// a lazy min-heap, merges, the topology checks and the saved vertices.
#include "collapse.hpp"
#include "collapse_queue.hpp"
#include "flip_test.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

namespace medax::qmat {

namespace {

constexpr double kSingular = 1e-12;  // |det A| at or below this is singular (authors' code)
constexpr double kFlipPenalty = 1e9;  // added to E when every candidate flips a face

using Entry = QueuedCollapse;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

class Simplifier {
 public:
  Simplifier(const MedialComplex& medial, const std::vector<char>& saved, const QmatOptions& options)
      : options_(options),
        unit_(options.unit_length > 0 ? options.unit_length : default_unit_length(medial)),
        mesh_(medial, unit_),
        saved_(medial.num_vertices(), 0),
        stamps_(medial.num_vertices(), 0),
        generators_(medial.generators),
        flip_test_(mesh_),
        queue_([this](Index lo, Index hi, std::uint32_t stamp_lo, std::uint32_t stamp_hi) {
          return stale(lo, hi, stamp_lo, stamp_hi);
        }) {
    InitialQuadrics q = initial_quadrics(mesh_, options_);
    slab_ = std::move(q.slab);
    add_ = std::move(q.add);
    invalid_faces_ = q.invalid_faces;
    // Parity with the authors' connection program: the queue is costed before the marking.
    if (options_.stale_saved_costs) queue_all_edges();
    if (!saved.empty()) saved_ = saved;
    any_saved_ = std::any_of(saved_.begin(), saved_.end(), [](char s) { return s != 0; });
    if (!options_.stale_saved_costs) queue_all_edges();
  }

  void run(std::size_t target, QmatReport& report, const std::function<void(double)>& progress);
  MedialComplex output(const MedialComplex& input) const;

 private:
  bool stale(Index lo, Index hi, std::uint32_t stamp_lo, std::uint32_t stamp_hi) const {
    return !mesh_.alive(lo) || !mesh_.alive(hi) || stamps_[lo] != stamp_lo || stamps_[hi] != stamp_hi;
  }
  std::optional<Entry> evaluate(Index i, Index j);
  Vec4 optimal_sphere(Index i, Index j, double& error);
  Vec4 cheapest(Index i, Index j, const SlabQuadric& q, bool avoid_flips, double& error);
  bool contractible(Index i, Index j) const;
  bool guard_refuses(Index i, Index j) const;
  bool link_condition(Index i, Index j) const;
  void collapse(const Entry& e);
  void queue_all_edges();
  void queue_edges_of(Index v);

  QmatOptions options_;
  double unit_;
  CollapseMesh mesh_;
  std::vector<SlabQuadric> slab_, add_;
  std::vector<char> saved_;
  std::vector<std::uint32_t> stamps_;
  std::vector<std::vector<Index>> generators_;
  bool any_saved_ = false;
  std::size_t invalid_faces_ = 0, dropped_ = 0;
  FlipTest flip_test_;
  CollapseQueue queue_;
};

/// The cheapest of mᵢ, mⱼ and their mean under q, skipping flipping ones when asked; when every
/// candidate flips, the cheapest plus the flip penalty.
Vec4 Simplifier::cheapest(Index i, Index j, const SlabQuadric& q, bool avoid_flips, double& error) {
  const Vec4 candidates[3] = {mesh_.spheres[i], mesh_.spheres[j], 0.5 * (mesh_.spheres[i] + mesh_.spheres[j])};
  std::optional<Vec4> best;
  std::optional<Vec4> best_any;
  double best_error = 0, best_any_error = 0;
  for (const Vec4& m : candidates) {
    const double e = q(m);
    if (!best_any || e < best_any_error) best_any = m, best_any_error = e;
    if (avoid_flips && flip_test_.flips(i, j, centre_of(m))) continue;
    if (!best || e < best_error) best = m, best_error = e;
  }
  if (best) {
    error = best_error;
    return *best;
  }
  error = best_any_error + kFlipPenalty;
  return *best_any;
}

/// §1.4: the minimiser of Q_e (+ add terms), or the best of the endpoints and their mean.
Vec4 Simplifier::optimal_sphere(Index i, Index j, double& error) {
  const SlabQuadric qe = slab_[i] + slab_[j];
  const bool faceless = mesh_.face_count(i, j) == 0;
  if (!faceless && !(std::abs(qe.A.determinant()) > kSingular)) return cheapest(i, j, qe, options_.flip_test, error);
  const SlabQuadric qa = qe + add_[i] + add_[j];
  const std::optional<Vec4> m = qa.minimiser(kSingular);
  const Vec4 sphere = m && m->w() > 0 ? *m : Vec4(0.5 * (mesh_.spheres[i] + mesh_.spheres[j]));
  if (options_.flip_test && flip_test_.flips(i, j, centre_of(sphere))) return cheapest(i, j, qa, true, error);
  error = qa(sphere);
  return sphere;
}

std::optional<Entry> Simplifier::evaluate(Index i, Index j) {
  if (saved_[i] && saved_[j]) return std::nullopt;  // two saved spheres never merge
  Entry e{0, std::min(i, j), std::max(i, j), 0, 0, Vec4::Zero()};
  e.stamp_lo = stamps_[e.lo];
  e.stamp_hi = stamps_[e.hi];
  double error = 0;
  if (saved_[i] || saved_[j]) {
    e.sphere = mesh_.spheres[saved_[i] ? i : j];  // collapse onto the saved sphere
    error = (slab_[i] + slab_[j])(e.sphere);
  } else {
    e.sphere = optimal_sphere(i, j, error);
  }
  const double gamma = stability_ratio(mesh_.spheres[i], mesh_.spheres[j]);
  e.cost = (error + options_.stability_weight) * gamma * gamma;
  return e;
}

/// §1.6 (a) and (b): an edge of an unfilled 3-cycle whose edges bound at most one face each (a
/// hole), or an edge to a curve tip (one edge, no face).
bool Simplifier::guard_refuses(Index i, Index j) const {
  for (Index end : {i, j})
    if (mesh_.neighbours(end).size() == 1 && !mesh_.has_faces(end)) return true;
  if (mesh_.face_count(i, j) > 1) return false;
  for (Index w : mesh_.common_neighbours(i, j))
    if (!mesh_.has_face(i, j, w) && mesh_.face_count(j, w) <= 1 && mesh_.face_count(w, i) <= 1) return true;
  return false;
}

/// Lk(i) ∩ Lk(j) = Lk(ij) for a 2-complex: the common neighbours are exactly the apexes of the
/// faces on ij, and no edge wx spans both a face iwx and a face jwx.
bool Simplifier::link_condition(Index i, Index j) const {
  const std::vector<Index> common = mesh_.common_neighbours(i, j);
  if (common.size() != mesh_.face_count(i, j)) return false;
  for (std::size_t a = 0; a < common.size(); ++a)
    for (std::size_t b = a + 1; b < common.size(); ++b)
      if (mesh_.has_face(i, common[a], common[b]) && mesh_.has_face(j, common[a], common[b])) return false;
  return true;
}

bool Simplifier::contractible(Index i, Index j) const {
  // With saved vertices the protocol simplifies until only they remain (VMAS §4): the guard
  // would hold other vertices back, so it is off then.
  if (options_.topology_guard && !any_saved_ && mesh_.live_vertices() <= options_.guard_below &&
      guard_refuses(i, j))
    return false;
  return !options_.link_condition || link_condition(i, j);
}

void Simplifier::queue_all_edges() {
  for (Index i = 0; i < mesh_.size(); ++i)
    for (Index j : mesh_.neighbours(i))
      if (i < j)
        if (auto e = evaluate(i, j)) queue_.push_unordered(*e);
  queue_.heapify();
}

void Simplifier::queue_edges_of(Index v) {
  for (Index n : mesh_.neighbours(v))
    if (auto e = evaluate(v, n)) queue_.push(*e);
}

void Simplifier::collapse(const Entry& e) {
  const Index keep = saved_[e.hi] && !saved_[e.lo] ? e.hi : e.lo;
  const Index gone = keep == e.lo ? e.hi : e.lo;
  mesh_.merge(keep, gone);
  mesh_.spheres[keep] = e.sphere;
  flip_test_.forget();
  slab_[keep] += slab_[gone];
  add_[keep] += add_[gone];
  saved_[keep] = saved_[keep] || saved_[gone];
  if (!generators_.empty()) {
    generators_[keep].insert(generators_[keep].end(), generators_[gone].begin(), generators_[gone].end());
    generators_[gone].clear();
  }
  ++stamps_[keep];
  queue_edges_of(keep);
}

void Simplifier::run(std::size_t target, QmatReport& report, const std::function<void(double)>& progress) {
  const std::size_t start = mesh_.live_vertices(), goal = std::max<std::size_t>(target, 1);
  const std::size_t todo = start > goal ? start - goal : 0;
  report.stopped_by = "queue";
  while (mesh_.live_vertices() > goal) {
    if (queue_.empty()) break;
    const Entry e = queue_.pop();
    if (stale(e.lo, e.hi, e.stamp_lo, e.stamp_hi)) continue;
    if (options_.max_cost > 0 && e.cost > options_.max_cost) {
      report.stopped_by = "max_cost";
      break;
    }
    if (!contractible(e.lo, e.hi)) {
      ++dropped_;
      continue;
    }
    collapse(e);
    report.last_cost = e.cost;
    ++report.collapses;
    if (progress && report.collapses % 4096 == 0) progress(double(report.collapses) / double(todo));
  }
  if (mesh_.live_vertices() <= goal) report.stopped_by = "target";
  report.final_vertices = mesh_.live_vertices();
  report.invalid_faces = invalid_faces_;
  report.dropped = dropped_;
}

MedialComplex Simplifier::output(const MedialComplex& input) const {
  MedialComplex out;
  std::vector<Index> old_of_new, new_of_old(mesh_.size(), 0);
  for (Index v = 0; v < mesh_.size(); ++v)
    if (mesh_.alive(v)) {
      new_of_old[v] = static_cast<Index>(old_of_new.size());
      old_of_new.push_back(v);
      out.centres.push_back(unit_ * centre_of(mesh_.spheres[v]));
      out.radii.push_back(unit_ * mesh_.spheres[v].w());
    }
  for (Index v : old_of_new)
    for (Index n : mesh_.neighbours(v))
      if (v < n) out.edges.push_back({new_of_old[v], new_of_old[n]});
  std::vector<Index> kept_faces;
  for (Index f = 0; f < mesh_.face_slots(); ++f)
    if (mesh_.face_alive(f)) {
      const Tri& t = mesh_.face(f);
      out.faces.push_back({new_of_old[t[0]], new_of_old[t[1]], new_of_old[t[2]]});
      kept_faces.push_back(mesh_.source_face(f));
    }
  out.vertex_props = input.vertex_props;
  out.vertex_props.select(old_of_new);
  out.edge_props = input.edge_props;
  out.edge_props.select(std::vector<Index>(out.edges.size(), kFreshRow));
  out.face_props = input.face_props;
  out.face_props.select(kept_faces);
  out.generator_kind = input.generator_kind;
  if (!generators_.empty())
    for (Index v : old_of_new) {
      std::vector<Index> g = generators_[v];
      std::sort(g.begin(), g.end());
      g.erase(std::unique(g.begin(), g.end()), g.end());
      out.generators.push_back(std::move(g));
    }
  return out;
}

}  // namespace

double default_unit_length(const MedialComplex& medial) {
  if (medial.num_vertices() == 0) return 1;
  Vec3 lo = medial.centres[0], hi = lo;
  for (std::size_t v = 0; v < medial.num_vertices(); ++v) {
    const Vec3 r = Vec3::Constant(medial.radii[v]);
    lo = lo.cwiseMin(medial.centres[v] - r);
    hi = hi.cwiseMax(medial.centres[v] + r);
  }
  const double d = (hi - lo).norm();
  return d > 0 ? d : 1;
}

MedialComplex simplify(const MedialComplex& medial, const std::vector<char>& saved, const QmatOptions& options,
                       QmatReport* report, const std::function<void(double)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  QmatReport local;
  QmatReport& r = report ? *report : local;
  r = QmatReport{};
  r.initial_vertices = medial.num_vertices();
  r.saved = static_cast<std::size_t>(std::count_if(saved.begin(), saved.end(), [](char s) { return s != 0; }));
  Simplifier simplifier(medial, saved, options);
  r.seconds_setup = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  simplifier.run(options.target_vertices, r, progress);
  r.seconds_collapse = seconds_since(t1);
  return simplifier.output(medial);
}

}  // namespace medax::qmat
