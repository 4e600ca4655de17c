#include "burn_1d.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>

namespace medax::et {

namespace {
constexpr double kInf1 = std::numeric_limits<double>::infinity();

/// Each vertex's incident (neighbour, edge) pairs, as a CSR table.
struct Adjacency {
  std::vector<std::size_t> begin;
  std::vector<std::pair<Index, Index>> arcs;
  std::size_t degree(std::size_t v) const { return begin[v + 1] - begin[v]; }
};

Adjacency adjacency(const Graph1D& graph) {
  const std::size_t nv = graph.points.size();
  Adjacency a;
  a.begin.assign(nv + 1, 0);
  for (const Segment& e : graph.edges) ++a.begin[e[0] + 1], ++a.begin[e[1] + 1];
  for (std::size_t v = 0; v < nv; ++v) a.begin[v + 1] += a.begin[v];
  a.arcs.resize(a.begin[nv]);
  std::vector<std::size_t> fill(a.begin.begin(), a.begin.end() - 1);
  for (std::size_t i = 0; i < graph.edges.size(); ++i) {
    const Segment& e = graph.edges[i];
    a.arcs[fill[e[0]]++] = {e[1], static_cast<Index>(i)};
    a.arcs[fill[e[1]]++] = {e[0], static_cast<Index>(i)};
  }
  return a;
}

/// Arrival times of the fire through distinct edges, sorted, in a CSR slot per vertex (at most
/// one arrival per incident edge), and the burn time they give each vertex.
class Arrivals {
 public:
  Arrivals(const Graph1D& graph, const Adjacency& adj)
      : graph_(graph), adj_(adj), store_(adj.arcs.size()), count_(graph.points.size(), 0) {}

  void add(std::size_t v, double t) {
    double* a = store_.data() + adj_.begin[v];
    std::size_t n = count_[v]++;
    while (n > 0 && a[n - 1] > t) a[n] = a[n - 1], --n;
    a[n] = t;
  }

  /// When `v` burns given the arrivals so far: a leaf at its ignition time, any vertex once all
  /// but one of its edges have brought the fire; never when anchored.
  double burn_time(std::size_t v) const {
    if (!graph_.anchored.empty() && graph_.anchored[v]) return kInf1;
    const std::size_t d = adj_.degree(v);
    double k = d <= 1 ? graph_.ignite[v] : kInf1;
    const double* a = store_.data() + adj_.begin[v];
    const std::size_t n = count_[v];
    if (d >= 1 && n >= 1 && n >= d - 1) k = std::min(k, d == 1 ? a[0] : a[d - 2]);
    return k;
  }

 private:
  const Graph1D& graph_;
  const Adjacency& adj_;
  std::vector<double> store_;
  std::vector<std::uint32_t> count_;
};
}  // namespace

std::vector<double> burn_1d(const Graph1D& graph) {
  const std::size_t nv = graph.points.size();
  if (graph.ignite.size() != nv) throw std::invalid_argument("burn_1d: one ignition time per vertex");
  const Adjacency adj = adjacency(graph);
  Arrivals arrivals(graph, adj);
  std::vector<double> key(nv, kInf1), bt(nv, kInf1);
  std::vector<char> burned(nv, 0), edge_burned(graph.edges.size(), 0);
  using Entry = std::pair<double, Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t v = 0; v < nv; ++v) {
    key[v] = arrivals.burn_time(v);
    if (key[v] < kInf1) queue.push({key[v], static_cast<Index>(v)});
  }
  while (!queue.empty()) {
    const auto [t, v] = queue.top();
    queue.pop();
    if (burned[v] || t != key[v]) continue;
    burned[v] = 1;
    bt[v] = t;
    for (std::size_t i = adj.begin[v]; i < adj.begin[v + 1]; ++i) {
      const auto [u, e] = adj.arcs[i];
      if (edge_burned[e] || burned[u]) continue;
      edge_burned[e] = 1;
      arrivals.add(u, t + (graph.points[u] - graph.points[v]).norm());
      const double k = arrivals.burn_time(u);
      if (k < key[u]) {
        key[u] = k;
        queue.push({k, u});
      }
    }
  }
  return bt;
}

std::vector<double> burn_1d_brute_force(const Graph1D& tree) {
  const std::size_t nv = tree.points.size();
  std::vector<std::vector<std::pair<Index, double>>> adj(nv);
  for (const Segment& e : tree.edges) {
    const double l = (tree.points[e[0]] - tree.points[e[1]]).norm();
    adj[e[0]].push_back({e[1], l});
    adj[e[1]].push_back({e[0], l});
  }
  // All-pairs tree distances and parents (BFS from every vertex).
  std::vector<std::vector<double>> dist(nv, std::vector<double>(nv, kInf1));
  std::vector<std::vector<Index>> parent(nv, std::vector<Index>(nv, 0xffffffffu));
  for (std::size_t s = 0; s < nv; ++s) {
    std::vector<Index> stack{static_cast<Index>(s)};
    dist[s][s] = 0;
    parent[s][s] = static_cast<Index>(s);
    while (!stack.empty()) {
      const Index x = stack.back();
      stack.pop_back();
      for (auto [y, l] : adj[x])
        if (dist[s][y] == kInf1) dist[s][y] = dist[s][x] + l, parent[s][y] = x, stack.push_back(y);
    }
  }
  std::vector<Index> leaves;
  for (std::size_t v = 0; v < nv; ++v)
    if (adj[v].size() <= 1) leaves.push_back(static_cast<Index>(v));
  std::vector<double> bt(nv, -kInf1);
  for (Index y : leaves)
    for (Index z : leaves) {
      if (dist[y][z] == kInf1) continue;
      // Walk the path y -> z (parents in the tree rooted at y).
      for (Index x = z;; x = parent[y][x]) {
        const double v = std::min(tree.ignite[y] + dist[x][y], tree.ignite[z] + dist[x][z]);
        bt[x] = std::max(bt[x], v);
        if (x == y) break;
      }
    }
  return bt;
}

}  // namespace medax::et
