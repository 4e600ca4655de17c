#include "refine_topology.hpp"

#include <medax/union_find.hpp>

#include <algorithm>
#include <map>
#include <utility>

namespace medax::msd::refine {
namespace {

using Directed = std::map<std::pair<Index, Index>, int>;

Directed directed_edges(const std::vector<Tri>& faces) {
  Directed directed;
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  return directed;
}

/// Around every vertex the faces (a, b, c) link b → c; a manifold vertex's links form one cycle.
bool single_fans(const std::vector<Tri>& faces) {
  std::map<Index, std::map<Index, Index>> next;
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) next[f[k]][f[(k + 1) % 3]] = f[(k + 2) % 3];
  for (const auto& [vertex, fan] : next) {
    std::size_t steps = 0;
    Index at = fan.begin()->first;
    do {
      const auto it = fan.find(at);
      if (it == fan.end()) return false;
      at = it->second;
      ++steps;
    } while (at != fan.begin()->first && steps <= fan.size());
    if (steps != fan.size()) return false;
  }
  return true;
}

}  // namespace

Borders border_loops(const std::vector<Tri>& faces) {
  const Directed directed = directed_edges(faces);
  std::multimap<Index, Index> outgoing;  // border halfedges a → b
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first})) outgoing.emplace(edge.first, edge.second);
  Borders borders;
  for (auto it = outgoing.begin(); it != outgoing.end(); it = outgoing.upper_bound(it->first))
    if (outgoing.count(it->first) > 1) borders.pinches.push_back(it->first);
  if (!borders.pinches.empty()) return borders;
  std::map<Index, Index> next(outgoing.begin(), outgoing.end());
  while (!next.empty()) {
    std::vector<Index> loop;
    Index at = next.begin()->first;  // the lowest id starts its loop: deterministic
    while (true) {
      const auto it = next.find(at);
      if (it == next.end()) break;
      loop.push_back(at);
      at = it->second;
      next.erase(it);
    }
    borders.loops.push_back(std::move(loop));
  }
  return borders;
}

std::vector<int> face_components(const std::vector<Tri>& faces, int* count) {
  UnionFind sets(faces.size());
  std::map<std::pair<Index, Index>, std::size_t> first_face;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Index a = faces[f][k], b = faces[f][(k + 1) % 3];
      const auto [it, inserted] = first_face.try_emplace({std::min(a, b), std::max(a, b)}, f);
      if (!inserted) sets.unite(static_cast<Index>(it->second), static_cast<Index>(f));
    }
  std::vector<int> component(faces.size(), -1);
  std::map<std::size_t, int> id;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto [it, inserted] = id.try_emplace(sets.find(static_cast<Index>(f)), static_cast<int>(id.size()));
    component[f] = it->second;
  }
  if (count) *count = static_cast<int>(id.size());
  return component;
}

bool closed_manifold(const std::vector<Tri>& faces) {
  for (const Tri& f : faces)
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return false;
  const Directed directed = directed_edges(faces);
  for (const auto& [edge, count] : directed)
    if (count != 1 || !directed.count({edge.second, edge.first})) return false;
  return single_fans(faces);
}

}  // namespace medax::msd::refine
