#include "burn.hpp"

#include <medax/union_find.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace medax::et {

BurnGraph build_burn_graph(const TriangleComplex& cx, double omega, int min_samples) {
  if (!(omega > 0) || !std::isfinite(omega)) throw std::invalid_argument("omega must be > 0");
  if (min_samples < 0) throw std::invalid_argument("min_samples must be >= 0");
  BurnGraph g;
  g.cx = &cx;
  g.vsec = compute_vertex_sectors(cx);
  const Index V = static_cast<Index>(cx.num_vertices());
  const std::size_t ne = cx.num_edges();

  g.sample_begin.resize(ne + 1);
  std::size_t total = V;
  for (std::size_t e = 0; e < ne; ++e) {
    g.sample_begin[e] = static_cast<Index>(total);
    const double l = (cx.points[cx.edges[e][1]] - cx.points[cx.edges[e][0]]).norm();
    const double n = std::max<double>(min_samples, std::floor(l / omega));
    total += static_cast<std::size_t>(n);
    if (total >= 0xfffffff0u)
      throw std::runtime_error("omega is too small for this complex (more than 4e9 graph nodes)");
  }
  g.sample_begin[ne] = static_cast<Index>(total);

  g.pos.resize(total);
  g.radius.resize(total);
  g.sample_edge.resize(total - V);
  for (Index v = 0; v < V; ++v) g.pos[v] = cx.points[v], g.radius[v] = cx.radii[v];
  for (std::size_t e = 0; e < ne; ++e) {
    const Index a = cx.edges[e][0], b = cx.edges[e][1];
    const Index n = g.sample_begin[e + 1] - g.sample_begin[e];
    for (Index k = 0; k < n; ++k) {
      const double s = double(k + 1) / double(n + 1);
      const Index id = g.sample_begin[e] + k;
      g.pos[id] = (1 - s) * cx.points[a] + s * cx.points[b];
      g.radius[id] = (1 - s) * cx.radii[a] + s * cx.radii[b];
      g.sample_edge[id - V] = static_cast<Index>(e);
    }
  }

  g.sector_begin.resize(total + 1);
  g.boundary.resize(total);
  g.sector_begin[0] = 0;
  for (Index v = 0; v < V; ++v) {
    g.sector_begin[v + 1] = g.vsec.sector_begin[v + 1];
    g.boundary[v] = g.vsec.boundary[v];
  }
  for (std::size_t id = V; id < total; ++id) {
    const Index k = cx.edge_degree(g.sample_edge[id - V]);
    g.sector_begin[id + 1] = g.sector_begin[id] + (k <= 2 ? 1 : k);
    g.boundary[id] = k == 1 ? 1 : 0;
  }
  return g;
}

std::size_t BurnGraph::count_arcs() const {
  std::size_t arcs = 0;
  for (std::size_t t = 0; t < cx->num_triangles(); ++t) {
    std::size_t n[3], sum = 0;
    for (int j = 0; j < 3; ++j) sum += n[j] = samples_on(cx->tri_edges[t][j]);
    const std::size_t nt = 3 + sum;
    std::size_t tri_arcs = nt * (nt - 1) / 2;
    for (int j = 0; j < 3; ++j) tri_arcs -= (n[j] + 2) * (n[j] + 1) / 2;
    arcs += tri_arcs + sum + 3;
  }
  return arcs;
}

namespace {

/// Indexed 4-ary min-heap of nodes keyed by (key[node], node): decrease-key in place, so the
/// heap never holds stale entries (the notes' lazy-deletion heap does the same work with more
/// memory traffic).
class NodeHeap {
 public:
  explicit NodeHeap(const std::vector<double>& key) : key_(key), where_(key.size(), kAbsent) {}
  bool empty() const { return heap_.empty(); }
  Index top() const { return heap_.front(); }
  /// Inserts `n` or moves it up after its key decreased.
  void update(Index n) {
    std::size_t i = where_[n];
    if (i == kAbsent) {
      i = heap_.size();
      heap_.push_back(n);
    }
    sift_up(i, n);
  }
  Index pop() {
    const Index top = heap_.front();
    where_[top] = kAbsent;
    const Index last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) sift_down(0, last);
    return top;
  }

 private:
  static constexpr std::size_t kAbsent = ~std::size_t(0);
  bool less(Index a, Index b) const { return key_[a] < key_[b] || (key_[a] == key_[b] && a < b); }
  void sift_up(std::size_t i, Index n) {
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!less(n, heap_[parent])) break;
      heap_[i] = heap_[parent];
      where_[heap_[i]] = i;
      i = parent;
    }
    heap_[i] = n;
    where_[n] = i;
  }
  void sift_down(std::size_t i, Index n) {
    const std::size_t size = heap_.size();
    for (;;) {
      const std::size_t first = 4 * i + 1;
      if (first >= size) break;
      std::size_t best = first;
      const std::size_t end = std::min(first + 4, size);
      for (std::size_t c = first + 1; c < end; ++c)
        if (less(heap_[c], heap_[best])) best = c;
      if (!less(heap_[best], n)) break;
      heap_[i] = heap_[best];
      where_[heap_[i]] = i;
      i = best;
    }
    heap_[i] = n;
    where_[n] = i;
  }
  const std::vector<double>& key_;
  std::vector<std::size_t> where_;
  std::vector<Index> heap_;
};

/// Per-node exposure test (§3): among the unburned sectors U, the bridges of H_v[U] are
/// exposed. Marks them burned and returns how many sectors stay unburned.
class Exposure {
 public:
  explicit Exposure(const BurnGraph& g) : g_(g) {}

  template <typename OnExposed>
  int expose(Index n, std::vector<char>& burned, OnExposed&& on_exposed) {
    const Index s0 = g_.sector_begin[n], ns = g_.sector_begin[n + 1] - s0;
    if (!g_.is_vertex(n)) {
      const Index k = g_.cx->edge_degree(g_.sample_edge[n - g_.num_vertices()]);
      if (k == 2) return burned[s0] ? 0 : 1;  // one self-loop: never exposed
      int unburned = 0;
      Index last = 0;
      for (Index i = 0; i < ns; ++i)
        if (!burned[s0 + i]) ++unburned, last = s0 + i;
      if (unburned == 1) {  // k = 1, or the last of k >= 3 parallel sectors
        burned[last] = 1;
        on_exposed(last);
        return 0;
      }
      return unburned;
    }
    // Vertex: bridges of H_v restricted to the unburned sectors.
    const VertexSectors& vs = g_.vsec;
    const int nh = vs.h_nodes[n];
    unburned_.clear();
    for (Index i = 0; i < ns; ++i)
      if (!burned[s0 + i]) unburned_.push_back(s0 + i);
    if (unburned_.empty()) return 0;
    if (unburned_.size() == 1) {
      const Index s = unburned_[0];
      if (vs.end_a[s] == vs.end_b[s]) return 1;
      burned[s] = 1;
      on_exposed(s);
      return 0;
    }
    exposed_.clear();
    for (std::size_t a = 0; a < unburned_.size(); ++a) {
      const Index s = unburned_[a];
      if (vs.end_a[s] == vs.end_b[s]) continue;
      UnionFind h(nh);
      for (std::size_t b = 0; b < unburned_.size(); ++b)
        if (b != a) h.unite(vs.end_a[unburned_[b]], vs.end_b[unburned_[b]]);
      if (h.find(vs.end_a[s]) != h.find(vs.end_b[s])) exposed_.push_back(s);
    }
    for (Index s : exposed_) {
      burned[s] = 1;
      on_exposed(s);
    }
    return static_cast<int>(unburned_.size() - exposed_.size());
  }

 private:
  const BurnGraph& g_;
  std::vector<Index> unburned_, exposed_;
};

/// The fire of one burn (§3): node and sector arrival times, what has burned, the queue of nodes
/// by arrival time, and the result being filled.
class Fire {
 public:
  explicit Fire(const BurnGraph& g)
      : g_(g),
        node_time_(g.num_nodes(), kInf),
        sector_time_(g.num_sectors(), kInf),
        node_burned_(g.num_nodes(), 0),
        sector_burned_(g.num_sectors(), 0),
        prime_sector_(g.num_nodes(), kNone),
        queue_(node_time_),
        exposure_(g) {
    r_.prime_node.assign(g.num_sectors(), kNone);
    r_.prime_tri.assign(g.num_sectors(), kNone);
    r_.burn_order.reserve(g.num_nodes());
  }

  /// Boundary nodes catch fire at their radius.
  void ignite_boundary() {
    for (Index n = 0; n < g_.num_nodes(); ++n)
      if (g_.boundary[n]) {
        node_time_[n] = g_.radius[n];
        queue_.update(n);
      }
  }

  /// Pops the earliest node; false when nothing reachable is left (only closed surfaces remain).
  bool step() {
    if (queue_.empty()) return false;
    const Index v = queue_.top();
    if (node_time_[v] == kInf) return false;
    queue_.pop();
    ++r_.pops;
    const double time = node_time_[v];
    if (prime_sector_[v] != kNone) sector_burned_[g_.sector_begin[v] + prime_sector_[v]] = 1;
    const int left = exposure_.expose(v, sector_burned_, [&](Index s) {
      sector_time_[s] = time;
      r_.prime_node[s] = kNone;
      r_.prime_tri[s] = kNone;
    });
    if (left == 0)
      burn_node(v, time);
    else
      wait_on_earliest_sector(v);
    return true;
  }

  std::size_t pops() const { return r_.pops; }

  BurnResult result() {
    r_.bt.resize(g_.num_nodes());
    for (std::size_t n = 0; n < r_.bt.size(); ++n) r_.bt[n] = node_burned_[n] ? node_time_[n] : kInf;
    return std::move(r_);
  }

 private:
  /// Every sector of `v` has burned: `v` burns and the fire moves on along its arcs.
  void burn_node(Index v, double time) {
    node_burned_[v] = 1;
    r_.burn_order.push_back(v);
    const Vec3 pv = g_.pos[v];
    for_each_arc(g_, v, [&](Index u, Index t) {
      if (node_burned_[u]) return;
      const Index s0 = g_.sector_begin[u];
      const Index ts = g_.sector_begin[u + 1] - s0 == 1 ? s0 : s0 + g_.local_sector(u, t);  // most nodes: one sector
      if (sector_burned_[ts]) return;
      ++r_.relaxations;
      const double h = time + (g_.pos[u] - pv).norm();
      if (h >= sector_time_[ts]) return;
      sector_time_[ts] = h;
      r_.prime_node[ts] = v;
      r_.prime_tri[ts] = t;
      if (h < node_time_[u]) {
        node_time_[u] = h;
        prime_sector_[u] = ts - s0;
        queue_.update(u);
      }
    });
  }

  /// Some sector of `v` is still unburned: `v` waits for the earliest of them.
  void wait_on_earliest_sector(Index v) {
    Index best = kNone;
    for (Index s = g_.sector_begin[v]; s < g_.sector_begin[v + 1]; ++s)
      if (!sector_burned_[s] && (best == kNone || sector_time_[s] < sector_time_[best])) best = s;
    prime_sector_[v] = best - g_.sector_begin[v];
    node_time_[v] = sector_time_[best];
    if (node_time_[v] < kInf) queue_.update(v);
  }

  const BurnGraph& g_;
  BurnResult r_;
  std::vector<double> node_time_, sector_time_;
  std::vector<char> node_burned_, sector_burned_;
  std::vector<Index> prime_sector_;
  NodeHeap queue_;
  Exposure exposure_;
};

}  // namespace

BurnResult burn(const BurnGraph& g, const std::function<void()>& cancel) {
  Fire fire(g);
  fire.ignite_boundary();
  while (fire.step())
    if (cancel && (fire.pops() & 0xffff) == 0) cancel();
  return fire.result();
}

std::vector<double> erosion_thickness(const BurnGraph& g, const BurnResult& r) {
  std::vector<double> et(g.num_nodes());
  for (std::size_t n = 0; n < et.size(); ++n) et[n] = r.bt[n] == kInf ? kInf : r.bt[n] - g.radius[n];
  return et;
}

}  // namespace medax::et
