#include "dual.hpp"

#include <algorithm>
#include <iterator>

namespace medax::vmas {

Adjacency cluster_adjacency(const std::vector<Segment>& graph_edges, const std::vector<int>& cluster_of,
                            std::size_t count) {
  std::vector<Segment> pairs;
  for (const Segment& e : graph_edges) {
    const int a = cluster_of[e[0]], b = cluster_of[e[1]];
    if (a < 0 || b < 0 || a == b) continue;
    pairs.push_back({static_cast<Index>(std::min(a, b)), static_cast<Index>(std::max(a, b))});
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Adjacency adj(count);
  for (const Segment& p : pairs) {
    adj[p[0]].push_back(p[1]);
    adj[p[1]].push_back(p[0]);
  }
  for (auto& list : adj) std::sort(list.begin(), list.end());
  return adj;
}

DualComplex dual_complex(const Adjacency& adj, TriangleRule rule, const std::vector<Tri>& triangles,
                         const std::vector<int>& cluster_of) {
  DualComplex d;
  for (Index a = 0; a < adj.size(); ++a)
    for (Index b : adj[a])
      if (a < b) d.edges.push_back({a, b});
  if (rule == TriangleRule::Cliques) {
    std::vector<Index> common;
    for (Index a = 0; a < adj.size(); ++a)
      for (Index b : adj[a]) {
        if (b <= a) continue;
        common.clear();
        std::set_intersection(adj[a].begin(), adj[a].end(), adj[b].begin(), adj[b].end(), std::back_inserter(common));
        for (Index c : common)
          if (c > b) d.faces.push_back({a, b, c});
      }
  } else if (rule == TriangleRule::Restricted) {
    for (const Tri& t : triangles) {
      const int x = cluster_of[t[0]], y = cluster_of[t[1]], z = cluster_of[t[2]];
      if (x < 0 || y < 0 || z < 0 || x == y || y == z || x == z) continue;
      Tri f{static_cast<Index>(x), static_cast<Index>(y), static_cast<Index>(z)};
      std::sort(f.begin(), f.end());
      d.faces.push_back(f);  // its three sides are mesh edges between the clusters: a 3-clique
    }
    std::sort(d.faces.begin(), d.faces.end());
    d.faces.erase(std::unique(d.faces.begin(), d.faces.end()), d.faces.end());
  }
  return d;
}

}  // namespace medax::vmas
