// The Q-MAT collapse loop (notes §1.4–1.6, §2.6): optimal sphere per edge, priority (E + k)·γ²,
// a lazy min-heap, merges, the topology checks and the saved vertices.
#include "collapse.hpp"
#include "collapse_queue.hpp"
#include "flip_test.hpp"

#include <medax/services/blocks.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

namespace medax::qmat {

namespace {

constexpr double kSingular = 1e-12;  // |det A| at or below this is singular (authors' code)
constexpr double kFlipPenalty = 1e9;  // added to E when every candidate flips a face
constexpr std::size_t kCostBlock = 1024;  // vertices per parallel block of the first costing

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
        queue_(stamps_) {
    InitialQuadrics q = initial_quadrics(mesh_, options_);
    slab_ = std::move(q.slab);
    add_ = std::move(q.add);
    add_of_ = std::move(q.add_of);
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
  // A vertex's stamp is the number of the change that last moved or killed it (see the queue).
  bool stale(const Entry& e) const { return stamps_[e.lo] > e.seq || stamps_[e.hi] > e.seq; }
  std::optional<Entry> evaluate(Index i, Index j, FlipTest& flips) const;
  Vec4 optimal_sphere(Index i, Index j, FlipTest& flips, double& error) const;
  Vec4 cheapest(Index i, Index j, const SlabQuadric& q, FlipTest* flips, double& error) const;
  bool contractible(Index i, Index j) const;
  bool guard_refuses(Index i, Index j) const;
  bool link_condition(Index i, Index j) const;
  bool has_add(Index v) const { return add_of_[v] != InitialQuadrics::kNoAdd; }
  SlabQuadric with_add_terms(SlabQuadric q, Index i, Index j) const;
  void merge_add_terms(Index keep, Index gone);
  void collapse(const Entry& e);
  void queue_all_edges();
  void queue_edges_of(Index v);

  QmatOptions options_;
  double unit_;
  CollapseMesh mesh_;
  std::vector<PackedQuadric> slab_;
  std::vector<SlabQuadric> add_;  // the add terms of the vertices that have some
  std::vector<Index> add_of_;     // per vertex: its add terms in add_, or kNoAdd
  std::vector<char> saved_;
  std::vector<std::uint32_t> stamps_;
  std::uint32_t changes_ = 0;  // collapses so far: the number of the mesh's last change
  std::vector<std::vector<Index>> generators_;
  bool any_saved_ = false;
  std::size_t invalid_faces_ = 0, dropped_ = 0;
  FlipTest flip_test_;
  CollapseQueue queue_;
};

/// The cheapest of mᵢ, mⱼ and their mean under q (ties: in that order), skipping flipping ones
/// when asked; when every candidate flips, the cheapest plus the flip penalty. The candidates are
/// tried from the cheapest on, so the flip test runs only until one passes (the errors are
/// finite: finite spheres and quadrics).
Vec4 Simplifier::cheapest(Index i, Index j, const SlabQuadric& q, FlipTest* flips, double& error) const {
  const Vec4 candidates[3] = {mesh_.spheres[i], mesh_.spheres[j], 0.5 * (mesh_.spheres[i] + mesh_.spheres[j])};
  const double errors[3] = {q(candidates[0]), q(candidates[1]), q(candidates[2])};
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return errors[a] < errors[b] || (errors[a] == errors[b] && a < b); });
  for (int k : order)
    if (!flips || !flips->flips(i, j, centre_of(candidates[k]))) {
      error = errors[k];
      return candidates[k];
    }
  error = errors[order[0]] + kFlipPenalty;
  return candidates[order[0]];
}

/// q + add_i + add_j. A vertex without add terms has zero ones, and x + (+0) = x bit for bit
/// (quadrics are sums started from +0, so no entry is −0): its term is left out.
SlabQuadric Simplifier::with_add_terms(SlabQuadric q, Index i, Index j) const {
  for (Index v : {i, j})
    if (has_add(v)) q += add_[add_of_[v]];
  return q;
}

/// add_keep += add_gone; onto a vertex without add terms (zero ones) that is add_gone itself.
void Simplifier::merge_add_terms(Index keep, Index gone) {
  if (!has_add(gone)) return;
  if (has_add(keep)) add_[add_of_[keep]] += add_[add_of_[gone]];
  else add_of_[keep] = add_of_[gone];
}

/// §1.4: the minimiser of Q_e (+ add terms), or the best of the endpoints and their mean. The
/// face count matters only when Q_e is singular. Without add terms Q_e + add is Q_e bit for bit,
/// so neither the sum nor the determinant is computed twice.
Vec4 Simplifier::optimal_sphere(Index i, Index j, FlipTest& flips, double& error) const {
  const SlabQuadric qe = slab_[i].plus(slab_[j]);
  const bool invertible = qe.invertible(kSingular);
  FlipTest* avoid = options_.flip_test ? &flips : nullptr;
  if (!invertible && mesh_.face_count(i, j) != 0) return cheapest(i, j, qe, avoid, error);
  const bool with_add = has_add(i) || has_add(j);
  const SlabQuadric qa = with_add ? with_add_terms(qe, i, j) : qe;
  const bool qa_invertible = with_add ? qa.invertible(kSingular) : invertible;
  const std::optional<Vec4> m = qa_invertible ? qa.solution() : std::nullopt;
  const Vec4 sphere = m && m->w() > 0 ? *m : Vec4(0.5 * (mesh_.spheres[i] + mesh_.spheres[j]));
  if (avoid && flips.flips(i, j, centre_of(sphere))) return cheapest(i, j, qa, avoid, error);
  error = qa(sphere);
  return sphere;
}

std::optional<Entry> Simplifier::evaluate(Index i, Index j, FlipTest& flips) const {
  if (saved_[i] && saved_[j]) return std::nullopt;  // two saved spheres never merge
  Entry e{0, std::min(i, j), std::max(i, j), changes_, Vec4::Zero()};
  double error = 0;
  if (saved_[i] || saved_[j]) {
    e.sphere = mesh_.spheres[saved_[i] ? i : j];  // collapse onto the saved sphere
    error = slab_[i].plus(slab_[j])(e.sphere);
  } else {
    e.sphere = optimal_sphere(i, j, flips, error);
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

/// Every edge's first cost depends only on the input, so blocks of vertices are costed in
/// parallel, each with its own flip test, and queued in vertex order: the heap is the same as
/// when costed in sequence, whatever the thread count.
void Simplifier::queue_all_edges() {
  const std::size_t n = mesh_.size();
  std::vector<std::vector<Entry>> blocks(services::block_count(n, kCostBlock));
  services::for_blocks(n, kCostBlock, options_.parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    FlipTest flips(mesh_);
    std::size_t edges = 0;
    for (auto i = static_cast<Index>(begin); i < end; ++i)
      for (Index j : mesh_.neighbours(i)) edges += i < j;
    blocks[b].reserve(edges);
    for (auto i = static_cast<Index>(begin); i < end; ++i)
      for (Index j : mesh_.neighbours(i))
        if (i < j)
          if (auto e = evaluate(i, j, flips)) blocks[b].push_back(*e);
  });
  std::size_t count = 0;
  for (const std::vector<Entry>& block : blocks) count += block.size();
  queue_.reserve(count);
  for (const std::vector<Entry>& block : blocks)
    for (const Entry& e : block) queue_.push_unordered(e);
  queue_.heapify();
}

/// Re-costs v's edges. The neighbours' quadrics, spheres and lists lie anywhere in memory: they
/// are all requested before the first edge is costed, so that their cache misses overlap.
void Simplifier::queue_edges_of(Index v) {
  for (Index n : mesh_.neighbours(v)) {
    __builtin_prefetch(&slab_[n]);
    __builtin_prefetch(reinterpret_cast<const char*>(&slab_[n]) + 64);
    mesh_.prefetch(n);
  }
  for (Index n : mesh_.neighbours(v))
    if (auto e = evaluate(v, n, flip_test_)) queue_.push(*e);
}

void Simplifier::collapse(const Entry& e) {
  const Index keep = saved_[e.hi] && !saved_[e.lo] ? e.hi : e.lo;
  const Index gone = keep == e.lo ? e.hi : e.lo;
  mesh_.merge(keep, gone);
  mesh_.spheres[keep] = e.sphere;
  flip_test_.forget();
  slab_[keep] += slab_[gone];
  merge_add_terms(keep, gone);
  saved_[keep] = saved_[keep] || saved_[gone];
  if (!generators_.empty()) {
    generators_[keep].insert(generators_[keep].end(), generators_[gone].begin(), generators_[gone].end());
    generators_[gone].clear();
  }
  stamps_[keep] = stamps_[gone] = ++changes_;
  queue_edges_of(keep);
}

void Simplifier::run(std::size_t target, QmatReport& report, const std::function<void(double)>& progress) {
  const std::size_t start = mesh_.live_vertices(), goal = std::max<std::size_t>(target, 1);
  const std::size_t todo = start > goal ? start - goal : 0;
  report.stopped_by = "queue";
  while (mesh_.live_vertices() > goal) {
    if (queue_.empty()) break;
    const Entry e = queue_.pop();
    if (stale(e)) continue;
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
