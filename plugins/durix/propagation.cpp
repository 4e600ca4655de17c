// The main loop (paper Algorithm 1, notes §3.0-3.3, §3.7): per pass, one seed per solid
// component, sheet propagation, ε tests of the neighbour sheets across singular paths (carving
// the insignificant ones), boundary simplification; passes repeat until one removes nothing.
#include "engine.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <optional>
#include <queue>
#include <unordered_set>

namespace medax::durix {

Engine::Engine(Dual& dual, const RegionOracle& oracle_, const DurixOptions& options_, DurixReport& report_,
               const CancelFn& check_cancelled_)
    : d(dual), oracle(oracle_), options(options_), report(report_), check_cancelled(check_cancelled_) {
  witness.assign(d.num_points(), kNoId);
  cell_mark.assign(d.num_cells(), 0);
  vertex_mark.assign(d.num_points(), 0);
  preferred_seed.assign(static_cast<std::size_t>(d.num_components()), kNoId);
}

EdgeId Engine::choose_seed(int component) const {
  const auto first_face = [&](CellId c) -> EdgeId {
    if (c == kNoId || !d.solid(c)) return kNoId;
    for (int p = 0; p < 6; ++p) {
      const EdgeId e = d.cell_edge(c, p);
      if (d.volumetric(e) && d.label(e) < 0) return e;
    }
    return kNoId;
  };
  EdgeId e = first_face(preferred_seed[static_cast<std::size_t>(component)]);
  if (e != kNoId) return e;
  // Fallback: the largest ball of the component with a free face.
  CellId best = kNoId;
  for (CellId c = 0; c < d.num_cells(); ++c) {
    if (!d.solid(c) || d.component(c) != component) continue;
    if (first_face(c) == kNoId) continue;
    if (best == kNoId || d.radius(c) > d.radius(best)) best = c;
  }
  return first_face(best);
}

bool Engine::carve_beyond(const HalfPath& path, EdgeId fx, std::unordered_set<HalfEdge, HalfEdgeHash>& done) {
  for (const HalfEdge& p : path.edges)
    if (d.volumetric(d.face(p))) done.insert(d.side_nbr(p));
  const std::vector<CellId> nodes = path_nodes(path);
  std::vector<CellId> ring, seeds;
  d.ring(fx, ring);
  for (CellId c : ring)
    if (!std::binary_search(nodes.begin(), nodes.end(), c)) seeds.push_back(c);
  switch (carve(nodes, seeds, true)) {
    case CarveOutcome::Removed: return true;
    case CarveOutcome::Significant: break;
    case CarveOutcome::NotSeparated: ++report.rejected_not_separated; break;
    case CarveOutcome::NonManifold: ++report.rejected_manifold; break;
    case CarveOutcome::TopologyChange: ++report.rejected_topology; break;
  }
  return false;
}

void Engine::grow_across_path(const HalfPath& path, std::deque<HalfEdge>& queue) {
  for (const HalfEdge& p : path.edges) {
    if (!d.is_medial_edge(p.t) || d.degree(p.t) != 2 || d.forced(p.t)) continue;
    const auto v = d.facet_vertices(p.t);
    EdgeId faces[2];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const EdgeId f = d.edge_of(p.t.cell, v[i], v[(i + 1) % 3]);
      if (d.volumetric(f) && n < 2) faces[n++] = f;
    }
    if (n != 2) continue;
    const int la = d.label(faces[0]), lb = d.label(faces[1]);
    if (la >= 0 && lb < 0) label_sheet(faces[1], la, &queue);
    else if (lb >= 0 && la < 0) label_sheet(faces[0], lb, &queue);
  }
}

std::size_t Engine::propagate(EdgeId seed) {
  std::deque<HalfEdge> queue;
  std::unordered_set<HalfEdge, HalfEdgeHash> done;
  std::size_t removed = 0;
  label_sheet(seed, next_label++, &queue);
  std::size_t steps = 0;
  while (!queue.empty()) {
    const HalfEdge e = queue.front();
    queue.pop_front();
    if ((++steps & 1023) == 0 && check_cancelled) check_cancelled();
    if (done.count(e) || !d.is_medial_edge(e.t)) continue;
    const EdgeId fe = d.face(e);
    if (!d.volumetric(fe) || d.label(fe) < 0) continue;
    if (d.degree(e.t) < 3 && !d.forced(e.t)) continue;
    const HalfEdge x = d.side_nbr(e);
    const EdgeId fx = d.face(x);
    if (d.label(fx) >= 0) continue;
    ++report.candidates;
    const HalfPath path = follow(x);
    if (!path.closed) ++report.path_failures;
    if (path.closed && carve_beyond(path, fx, done)) {
      ++removed;
      ++report.removals;
      grow_across_path(path, queue);
    } else {
      label_sheet(fx, next_label++, &queue);
    }
  }
  return removed;
}

namespace {

/// A boundary node to try carving: the tip of a sharp turn of the sheet's boundary.
struct Spike {
  double saliency;
  CellId tip;
  bool operator<(const Spike& o) const {
    return saliency != o.saliency ? saliency > o.saliency : tip > o.tip;  // the sharpest on top
  }
};

/// Consecutive boundary half-edges (h, h_a) turning sharper than 90° at their common node (the
/// tip), turning towards the sheet; the saliency is ‖û × â‖ (notes §3.7). Nothing otherwise.
std::optional<Spike> boundary_spike(const Engine& engine, const HalfEdge& h) {
  const Dual& d = engine.d;
  if (!d.is_medial_edge(h.t) || !engine.boundary_half_edge(h) || d.label(d.face(h)) < 0) return std::nullopt;
  const CellId s = d.start(h), tip = d.end(h);
  // The boundary successor at the tip, on the same side.
  HalfEdge g = d.next(h);
  for (int i = 0; i < 64 && !engine.boundary_half_edge(g); ++i) g = d.next(d.side_nbr(g));
  if (!engine.boundary_half_edge(g)) return std::nullopt;
  const Vec3 c0 = d.centre(s), c1 = d.centre(tip), c2 = d.centre(d.end(g));
  const Vec3 inner = d.centre(d.end(d.next(h)));
  Vec3 u = c1 - c0, a = c2 - c1;
  const double lu = u.norm(), la = a.norm();
  if (lu <= 0 || la <= 0) return std::nullopt;
  u /= lu;
  a /= la;
  const Vec3 n = u.cross(inner - c1);
  const Vec3 ua = u.cross(a);
  if (ua.dot(n) <= 0 || u.dot(a) >= 0) return std::nullopt;
  return Spike{ua.norm(), tip};
}

/// The tip's solid neighbours (sorted) when it has at least two surface facets; none otherwise.
std::vector<CellId> carvable_tip_neighbours(const Dual& d, CellId tip) {
  std::vector<CellId> neighbours;
  int surface = 0;
  for (int k = 0; k < 4; ++k) {
    const CellId n = d.neighbour(tip, k);
    if (d.solid(n)) neighbours.push_back(n);
    else ++surface;
  }
  if (surface < 2) return {};
  std::sort(neighbours.begin(), neighbours.end());
  return neighbours;
}

}  // namespace

std::size_t Engine::simplify_boundaries() {
  // Candidates: sharp boundary turns, the sharpest first (notes §3.7).
  std::priority_queue<Spike> heap;
  const auto consider = [&](const HalfEdge& h) {
    if (const auto spike = boundary_spike(*this, h)) heap.push(*spike);
  };
  std::vector<Facet> facets;
  for (EdgeId e = 0; e < d.num_edges(); ++e) {
    if (!d.volumetric(e) || d.label(e) < 0) continue;
    const Index a = d.edge_vertices(e)[0], b = d.edge_vertices(e)[1];
    d.ring_facets(e, facets);
    for (const Facet& t : facets)
      if (d.degree(t) == 1) {
        consider({t, a, b});
        consider({t, b, a});
      }
  }
  std::size_t removed = prune_leaves(), steps = 0;
  while (!heap.empty()) {
    const CellId tip = heap.top().tip;
    heap.pop();
    if ((++steps & 255) == 0 && check_cancelled) check_cancelled();
    if (!d.solid(tip)) continue;
    const std::vector<CellId> neighbours = carvable_tip_neighbours(d, tip);
    if (neighbours.empty() || carve(neighbours, {tip}, false) != CarveOutcome::Removed) continue;
    ++removed;
    ++report.boundary_removals;
    // New boundary half-edges around the neighbours.
    for (CellId n : neighbours)
      for (int k = 0; k < 4; ++k) {
        const Facet t = d.facet(n, k);
        if (d.solid(d.neighbour(n, k)) && d.degree(t) == 1) d.for_each_half_edge(t, consider);
      }
  }
  return removed;
}

std::size_t Engine::prune_leaves() {
  // The one-dimensional analogue of boundary simplification (notes §3.9, 1D sheets): a node with
  // three surface facets ends a curve; carving it removes its apex vertex, which must be covered
  // within ε by the ball of the node it hangs from.
  std::deque<CellId> queue;
  const auto leaf_parent = [&](CellId c) {
    CellId parent = kNoId;
    for (int k = 0; k < 4; ++k) {
      const CellId n = d.neighbour(c, k);
      if (!d.solid(n)) continue;
      if (parent != kNoId) return kNoId;
      parent = n;
    }
    return parent;
  };
  for (CellId c = 0; c < d.num_cells(); ++c)
    if (d.solid(c) && leaf_parent(c) != kNoId) queue.push_back(c);
  std::size_t removed = 0;
  while (!queue.empty()) {
    const CellId c = queue.front();
    queue.pop_front();
    if (!d.solid(c)) continue;
    const CellId parent = leaf_parent(c);
    if (parent == kNoId) continue;
    if (carve({parent}, {c}, false) != CarveOutcome::Removed) continue;
    ++removed;
    ++report.leaves_pruned;
    if (leaf_parent(parent) != kNoId) queue.push_back(parent);
  }
  return removed;
}

std::size_t Engine::pass() {
  d.clear_labels();
  next_label = 0;
  std::size_t removed = options.remove_outside_centres ? remove_outside_centres() : 0;
  for (int comp = 0; comp < d.num_components(); ++comp) {
    const EdgeId seed = choose_seed(comp);
    if (seed != kNoId) removed += propagate(seed);
  }
  // Faces reached from no seed through singular paths (attached through a node or a curve).
  for (EdgeId e = 0; e < d.num_edges(); ++e)
    if (d.volumetric(e) && d.label(e) < 0) removed += propagate(e);
  if (options.simplify_boundaries) {
    const std::size_t b = simplify_boundaries();
    removed += b;
  }
  return removed;
}

void Engine::run_passes(const ProgressFn& progress) {
  for (int i = 0; i < std::max(1, options.max_passes); ++i) {
    if (progress) progress(0.1 + 0.6 * i / std::max(1, options.max_passes), "propagation pass");
    ++report.passes;
    if (pass() == 0) break;
    if (i + 1 == options.max_passes) {
      // The last pass carved something: relabel once more without carving so that the labels
      // match the final solid.
      d.clear_labels();
      next_label = 0;
      for (EdgeId e = 0; e < d.num_edges(); ++e)
        if (d.volumetric(e) && d.label(e) < 0) label_sheet(e, next_label++, nullptr);
    }
  }
}

void Engine::run(const ProgressFn& progress) {
  peel_flat_cells();
  run_passes(progress);
  // §4.7 once at the end, as in the paper: the pieces it splits off are not tested against ε
  // again (they are not sheets of the shape but cuts through one; testing them carved real
  // features piece by piece, e.g. a bump of height 2ε).
  const auto t0 = std::chrono::steady_clock::now();
  if (options.split_problematic) split_problematic();
  report.seconds_problematic = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  census_paths();
}

}  // namespace medax::durix
