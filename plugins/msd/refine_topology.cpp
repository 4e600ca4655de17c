#include "refine_topology.hpp"

#include <medax/union_find.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <tuple>
#include <utility>

namespace medax::msd::refine {
namespace {

// Halfedges a → b as sorted 64-bit keys: binary searches instead of tree maps (these run for
// every join attempt of every primitive).
std::uint64_t key(Index a, Index b) { return (std::uint64_t{a} << 32) | b; }
Index source(std::uint64_t k) { return static_cast<Index>(k >> 32); }
Index target(std::uint64_t k) { return static_cast<Index>(k & 0xffffffffu); }

std::vector<std::uint64_t> sorted_halfedges(const std::vector<Tri>& faces) {
  std::vector<std::uint64_t> halfedges;
  halfedges.reserve(3 * faces.size());
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) halfedges.push_back(key(f[k], f[(k + 1) % 3]));
  std::sort(halfedges.begin(), halfedges.end());
  return halfedges;
}

bool contains(const std::vector<std::uint64_t>& sorted, std::uint64_t k) {
  return std::binary_search(sorted.begin(), sorted.end(), k);
}

/// Around every vertex a the faces (a, b, c) link b → c; a manifold vertex's links form one cycle.
bool single_fans(const std::vector<Tri>& faces) {
  std::vector<std::tuple<Index, Index, Index>> links;  // (a, b, c)
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) links.emplace_back(f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
  std::sort(links.begin(), links.end());
  for (auto begin = links.begin(); begin != links.end();) {
    const Index a = std::get<0>(*begin);
    const auto end = std::find_if(begin, links.end(), [&](const auto& l) { return std::get<0>(l) != a; });
    const auto size = static_cast<std::size_t>(end - begin);
    std::size_t steps = 0;
    Index at = std::get<1>(*begin);
    do {
      const auto it = std::lower_bound(begin, end, std::make_tuple(a, at, Index{0}));
      if (it == end || std::get<1>(*it) != at) return false;
      at = std::get<2>(*it);
      ++steps;
    } while (at != std::get<1>(*begin) && steps <= size);
    if (steps != size) return false;
    begin = end;
  }
  return true;
}

}  // namespace

Borders border_loops(const std::vector<Tri>& faces) {
  const std::vector<std::uint64_t> halfedges = sorted_halfedges(faces);
  std::vector<std::uint64_t> border;  // sorted, since halfedges are
  for (std::uint64_t h : halfedges)
    if (!contains(halfedges, key(target(h), source(h)))) border.push_back(h);
  Borders borders;
  for (std::size_t i = 1; i < border.size(); ++i)
    if (source(border[i]) == source(border[i - 1]) &&
        (borders.pinches.empty() || borders.pinches.back() != source(border[i])))
      borders.pinches.push_back(source(border[i]));
  if (!borders.pinches.empty()) return borders;
  std::vector<char> used(border.size(), 0);
  for (std::size_t first = 0; first < border.size(); ++first) {
    if (used[first]) continue;  // the lowest unused id starts its loop: deterministic
    std::vector<Index> loop;
    std::size_t at = first;
    while (!used[at]) {
      used[at] = 1;
      loop.push_back(source(border[at]));
      const auto next = std::lower_bound(border.begin(), border.end(), key(target(border[at]), 0));
      if (next == border.end() || source(*next) != target(border[at])) break;
      at = static_cast<std::size_t>(next - border.begin());
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
  const std::vector<std::uint64_t> halfedges = sorted_halfedges(faces);
  if (std::adjacent_find(halfedges.begin(), halfedges.end()) != halfedges.end()) return false;
  for (std::uint64_t h : halfedges)
    if (!contains(halfedges, key(target(h), source(h)))) return false;
  return single_fans(faces);
}

}  // namespace medax::msd::refine
