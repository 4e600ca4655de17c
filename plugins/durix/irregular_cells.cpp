// Appendix A irregularities of the discrete skeleton (notes §3.9): cells whose ball says nothing
// about the shape, removed from the solid at its surface.
//   flat cells      four cocircular corners, no true sphere: peeled when they have two surface
//                   facets (a flip of a planar quad's diagonal, no vertex moves)
//   outside centres cells whose circumcentre lies outside the input (coarse sampling, near-flat
//                   cells): "removed by removing the associated tetrahedra"
#include "engine.hpp"

#include <algorithm>
#include <deque>

namespace medax::durix {

std::size_t Engine::peel_flat_cells() {
  std::deque<CellId> queue;
  for (CellId c = 0; c < d.num_cells(); ++c)
    if (d.solid(c) && d.flat(c)) queue.push_back(c);
  std::size_t peeled = 0;
  while (!queue.empty()) {
    const CellId c = queue.front();
    queue.pop_front();
    if (!d.solid(c)) continue;
    std::vector<CellId> neighbours;
    for (int k = 0; k < 4; ++k)
      if (d.solid(d.neighbour(c, k))) neighbours.push_back(d.neighbour(c, k));
    if (neighbours.size() != 2) continue;  // exactly two surface facets: a flip
    std::sort(neighbours.begin(), neighbours.end());
    if (carve(neighbours, {c}, false, false) != CarveOutcome::Removed) continue;
    ++peeled;
    for (CellId n : neighbours)
      if (d.flat(n)) queue.push_back(n);
  }
  report.flat_cells_peeled += peeled;
  return peeled;
}

std::size_t Engine::remove_outside_centres() {
  // A cluster (connected through solid facets) of outside-centre cells reaching the surface is
  // carved into the kept cells around it. The carving's ε test (every vertex of the cluster
  // within ε of a kept ball) guards the shape and ties the removal to ε > 0, as Fig. 16 (ε = 0)
  // still shows outside peaks; its manifold and topology checks guard M_w. Whole clusters,
  // because one cell with a single surface facet cannot leave alone: its apex is already on the
  // surface, so M_w would pinch there.
  if (centre_inside.empty()) return 0;
  // Marks: a cell of some cluster (for the whole sweep: tried once), or a kept cell around the
  // current cluster (reset after it, as it may border other clusters).
  enum : char { kFree = 0, kClustered = 1, kKeptHere = 2 };
  std::vector<char> mark(d.num_cells(), kFree);
  std::size_t removed = 0;
  std::vector<CellId> cluster, kept;
  for (CellId c0 = 0; c0 < d.num_cells(); ++c0) {
    if (!d.solid(c0) || centre_inside[c0] || mark[c0] != kFree) continue;
    bool at_surface = false;
    for (int k = 0; k < 4; ++k) at_surface |= !d.solid(d.neighbour(c0, k));
    if (!at_surface) continue;
    cluster.assign(1, c0);
    kept.clear();
    mark[c0] = kClustered;
    for (std::size_t i = 0; i < cluster.size(); ++i)
      for (int k = 0; k < 4; ++k) {
        const CellId n = d.neighbour(cluster[i], k);
        if (!d.solid(n) || mark[n] != kFree) continue;
        mark[n] = centre_inside[n] ? kKeptHere : kClustered;
        (centre_inside[n] ? kept : cluster).push_back(n);
      }
    for (CellId n : kept) mark[n] = kFree;
    if (kept.empty()) continue;  // a whole component: nothing to carve into
    std::sort(kept.begin(), kept.end());
    if (carve(kept, cluster, false) == CarveOutcome::Removed) removed += cluster.size();
  }
  report.outside_centres_removed += removed;
  return removed;
}

}  // namespace medax::durix
