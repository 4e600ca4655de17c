#include "refine_band.hpp"

#include "refine_stitch.hpp"
#include "refine_topology.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>

namespace medax::msd::refine {
namespace {

/// Mean over the patch loop of the distance on ∂P^ρ0 to the nearest vertex of the other loop.
double loop_distance(const std::vector<Index>& patch_loop, const std::vector<Index>& other,
                     const std::vector<FramedPoint>& points) {
  double total = 0;
  for (Index a : patch_loop) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Index b : other) nearest = std::min(nearest, (points[a].projected - points[b].projected).norm());
    total += nearest;
  }
  return total / static_cast<double>(patch_loop.size());
}

/// The component (of `remaining`) each border loop belongs to: that of a face holding its first
/// border halfedge.
std::vector<int> loop_components(const std::vector<std::vector<Index>>& loops, const std::vector<Tri>& faces,
                                 const std::vector<int>& component) {
  std::map<std::pair<Index, Index>, int> of_halfedge;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) of_halfedge[{faces[f][k], faces[f][(k + 1) % 3]}] = component[f];
  std::vector<int> result;
  for (const auto& loop : loops) result.push_back(of_halfedge.at({loop[0], loop[1 % loop.size()]}));
  return result;
}

/// Greedy pairing by increasing distance: pair[p] is the remaining loop of patch loop p or −1.
std::vector<int> pair_loops(const std::vector<std::vector<Index>>& patch_loops,
                            const std::vector<std::vector<Index>>& template_loops, const std::vector<FramedPoint>& points) {
  std::vector<std::tuple<double, int, int>> candidates;
  for (std::size_t p = 0; p < patch_loops.size(); ++p)
    for (std::size_t t = 0; t < template_loops.size(); ++t)
      candidates.emplace_back(loop_distance(patch_loops[p], template_loops[t], points), static_cast<int>(p),
                              static_cast<int>(t));
  std::sort(candidates.begin(), candidates.end());
  std::vector<int> pair(patch_loops.size(), -1);
  std::vector<char> taken(template_loops.size(), 0);
  for (const auto& [distance, p, t] : candidates)
    if (pair[p] < 0 && !taken[t]) {
      pair[p] = t;
      taken[t] = 1;
    }
  return pair;
}

}  // namespace

Closure close_band(const std::vector<Tri>& remaining, const std::vector<Tri>& patch,
                   const std::vector<FramedPoint>& points) {
  Closure closure;
  const Borders patch_borders = border_loops(patch), template_borders = border_loops(remaining);
  if (!template_borders.pinches.empty()) return {{}, {}, "the removed template region pinches", {}};
  int count = 0;
  const std::vector<int> component = face_components(remaining, &count);
  const std::vector<int> loop_component = loop_components(template_borders.loops, remaining, component);
  const std::vector<int> pair = pair_loops(patch_borders.loops, template_borders.loops, points);
  // Each patch border gets a band to its template border, or else a cap; the template
  // components kept are those a band joins, and every border of a kept one must be joined.
  std::vector<char> keep(count, 0), joined(template_borders.loops.size(), 0);
  for (std::size_t p = 0; p < pair.size(); ++p) {
    auto band = pair[p] < 0 ? std::nullopt : stitch_band(patch_borders.loops[p], template_borders.loops[pair[p]], points);
    if (band) {
      joined[pair[p]] = 1;
      keep[loop_component[pair[p]]] = 1;
    } else {
      band = cap_loop(patch_borders.loops[p], points);
    }
    if (!band) {  // every failing border is reported, so that one retry can fix them all
      if (closure.failure.empty())
        closure.failure = fmt::format("no consistent band or cap for patch border {} ({} vertices)", p,
                                      patch_borders.loops[p].size());
      closure.failed_loop.insert(closure.failed_loop.end(), patch_borders.loops[p].begin(), patch_borders.loops[p].end());
      continue;
    }
    closure.band.insert(closure.band.end(), band->begin(), band->end());
  }
  if (!closure.failure.empty()) return {{}, {}, closure.failure, closure.failed_loop};
  for (std::size_t t = 0; t < joined.size(); ++t)
    if (keep[loop_component[t]] && !joined[t])
      return {{}, {}, "a template component keeps a border no patch border joins", {}};
  for (std::size_t f = 0; f < remaining.size(); ++f)
    if (keep[component[f]]) closure.remaining.push_back(remaining[f]);
  return closure;
}

}  // namespace medax::msd::refine
