#include "burn_1d.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>

namespace medax::et {

namespace {
constexpr double kInf1 = std::numeric_limits<double>::infinity();
}

std::vector<double> burn_1d(const Graph1D& graph) {
  const std::size_t nv = graph.points.size();
  if (graph.ignite.size() != nv) throw std::invalid_argument("burn_1d: one ignition time per vertex");
  const bool has_anchor = !graph.anchored.empty();
  // Adjacency (CSR) with edge ids.
  std::vector<std::size_t> begin(nv + 1, 0);
  for (const Segment& e : graph.edges) ++begin[e[0] + 1], ++begin[e[1] + 1];
  for (std::size_t v = 0; v < nv; ++v) begin[v + 1] += begin[v];
  std::vector<std::pair<Index, Index>> adj(begin[nv]);  // (neighbour, edge)
  std::vector<std::size_t> fill(begin.begin(), begin.end() - 1);
  for (std::size_t i = 0; i < graph.edges.size(); ++i) {
    const Segment& e = graph.edges[i];
    adj[fill[e[0]]++] = {e[1], static_cast<Index>(i)};
    adj[fill[e[1]]++] = {e[0], static_cast<Index>(i)};
  }

  // Arrival times of the fire through distinct edges, sorted, in a CSR slot per vertex (at most
  // one arrival per incident edge).
  std::vector<double> arrival_store(begin[nv]);
  std::vector<std::uint32_t> arrival_count(nv, 0);
  std::vector<double> key(nv, kInf1), bt(nv, kInf1);
  std::vector<char> burned(nv, 0), edge_burned(graph.edges.size(), 0);
  using Entry = std::pair<double, Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  auto degree = [&](std::size_t v) { return begin[v + 1] - begin[v]; };
  auto candidate = [&](std::size_t v) {
    if (has_anchor && graph.anchored[v]) return kInf1;
    const std::size_t d = degree(v);
    double k = d <= 1 ? graph.ignite[v] : kInf1;
    const double* a = arrival_store.data() + begin[v];
    const std::size_t n = arrival_count[v];
    if (d >= 1 && n >= 1 && n >= d - 1) k = std::min(k, d == 1 ? a[0] : a[d - 2]);
    return k;
  };
  for (std::size_t v = 0; v < nv; ++v) {
    key[v] = candidate(v);
    if (key[v] < kInf1) queue.push({key[v], static_cast<Index>(v)});
  }
  while (!queue.empty()) {
    const auto [t, v] = queue.top();
    queue.pop();
    if (burned[v] || t != key[v]) continue;
    burned[v] = 1;
    bt[v] = t;
    for (std::size_t i = begin[v]; i < begin[v + 1]; ++i) {
      const auto [u, e] = adj[i];
      if (edge_burned[e] || burned[u]) continue;
      edge_burned[e] = 1;
      const double len = (graph.points[u] - graph.points[v]).norm();
      double* a = arrival_store.data() + begin[u];
      std::size_t n = arrival_count[u]++;
      while (n > 0 && a[n - 1] > t + len) a[n] = a[n - 1], --n;
      a[n] = t + len;
      const double k = candidate(u);
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
