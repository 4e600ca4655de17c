// The region beyond a singular path, its ε test and its carving (paper §3.5, §4.5, Fig. 12;
// notes §3.5-3.6, the canonical tet-flood variant): flood the solid cells from the candidate
// sheet without entering the path's nodes; stop as soon as a cell touches the computed skeleton
// (the path does not separate) or a vertex is not covered within ε by the path's balls (the
// sheet is significant). Otherwise the flooded cells leave the solid: the surface faces they
// had (C) are replaced by the facets between them and the path's cells (D), which are interior
// Delaunay facets, so M_w stays a Delaunay mesh. The carving is validated (closed 2-manifold,
// and, by default, the same Euler characteristic) and rolled back when it fails.
#include "engine.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <limits>

namespace medax::durix {

CarveOutcome Engine::carve(const std::vector<CellId>& path, const std::vector<CellId>& seeds, bool stop_at_labels,
                           bool test_coverage) {
  if (test_coverage && oracle.epsilon() <= 0) return CarveOutcome::Significant;
  if (stamp > std::numeric_limits<std::uint32_t>::max() - 8) {
    std::fill(cell_mark.begin(), cell_mark.end(), 0);
    std::fill(vertex_mark.begin(), vertex_mark.end(), 0);
    stamp = 0;
  }
  const std::uint32_t path_stamp = ++stamp, region_stamp = ++stamp, vertex_stamp = ++stamp;
  std::vector<Ball> balls;
  balls.reserve(path.size());
  for (CellId c : path) {
    cell_mark[c] = path_stamp;
    balls.push_back({d.centre(c), d.radius(c)});
    for (Index v : d.cell(c)) vertex_mark[v] = vertex_stamp;  // on the path's spheres
  }
  std::size_t hint = 0;
  const auto covered = [&](Index v) { return !test_coverage || oracle.covered(d.point(v), balls, hint); };

  std::vector<CellId> region;
  for (CellId s : seeds)
    if (d.solid(s) && cell_mark[s] != path_stamp && cell_mark[s] != region_stamp) {
      cell_mark[s] = region_stamp;
      region.push_back(s);
    }
  if (region.empty()) return CarveOutcome::NotSeparated;
  for (std::size_t i = 0; i < region.size(); ++i) {
    const CellId c = region[i];
    if ((i & 4095) == 4095 && check_cancelled) check_cancelled();
    if (stop_at_labels)
      for (int p = 0; p < 6; ++p) {
        const EdgeId e = d.cell_edge(c, p);
        if (d.volumetric(e) && d.label(e) >= 0) return CarveOutcome::NotSeparated;
      }
    for (Index v : d.cell(c))
      if (vertex_mark[v] != vertex_stamp) {
        vertex_mark[v] = vertex_stamp;
        if (!covered(v)) return CarveOutcome::Significant;
      }
    if (const auto it = attached.find(c); it != attached.end())
      for (Index v : it->second)
        if (!covered(v)) return CarveOutcome::Significant;
    for (int k = 0; k < 4; ++k) {
      const CellId n = d.neighbour(c, k);
      if (d.solid(n) && cell_mark[n] != path_stamp && cell_mark[n] != region_stamp) {
        cell_mark[n] = region_stamp;
        region.push_back(n);
      }
    }
  }

  // Elements whose surface status may change.
  std::vector<EdgeId> edges;
  std::vector<Facet> facets;
  std::vector<Index> verts;
  for (CellId c : region) {
    for (int p = 0; p < 6; ++p) edges.push_back(d.cell_edge(c, p));
    for (int k = 0; k < 4; ++k) facets.push_back(d.facet(c, k));
    for (Index v : d.cell(c)) verts.push_back(v);
  }
  const auto unique = [](auto& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  unique(edges);
  unique(facets);
  unique(verts);
  const auto euler = [&]() {
    long long chi = 0;
    for (Index v : verts) chi += d.on_surface(v);
    for (EdgeId e : edges) chi -= d.surface_edge(e);
    for (const Facet& f : facets) chi += d.is_surface_facet(f);
    return chi;
  };
  const long long chi_before = euler();

  static const bool debug = std::getenv("MEDAX_DURIX_DEBUG") != nullptr;
  if (debug && d.verify_counters()) throw std::logic_error("counters broken before carve");
  for (CellId c : region) d.set_solid(c, false);
  if (debug && d.verify_counters()) throw std::logic_error("counters broken after set_solid");
  const auto rollback = [&](CarveOutcome outcome) {
    for (CellId c : region) d.set_solid(c, true);
    if (debug && d.verify_counters()) throw std::logic_error("counters broken after rollback");
    return outcome;
  };

  // Edge-manifold: every affected edge has 0 or 2 surface facets around it.
  std::vector<CellId> ring;
  for (EdgeId e : edges) {
    if (d.solid_count_of(e) == 0) continue;
    d.ring(e, ring);
    std::size_t transitions = 0;
    for (std::size_t i = 0; i < ring.size(); ++i)
      transitions += d.solid(ring[i]) != d.solid(ring[(i + 1) % ring.size()]);
    if (transitions != 0 && transitions != 2) return rollback(CarveOutcome::NonManifold);
  }
  // Vertex-manifold: the surface facets around each affected vertex form one disk.
  std::vector<std::pair<Index, Index>> link;
  for (Index v : verts) {
    if (!d.on_surface(v)) continue;
    link.clear();
    for (const CellId* it = d.vertex_cells_begin(v); it != d.vertex_cells_end(v); ++it) {
      const CellId c = *it;
      if (!d.solid(c)) continue;
      const auto& q = d.cell(c);
      for (int k = 0; k < 4; ++k) {
        if (q[k] == v || d.solid(d.neighbour(c, k))) continue;
        Index x = kNoId, y = kNoId;
        for (int j = 0; j < 4; ++j)
          if (j != k && q[j] != v) (x == kNoId ? x : y) = q[j];
        link.emplace_back(x, y);
      }
    }
    // Walk the link cycle from its first segment; it must use every segment once.
    if (link.size() < 3) return rollback(CarveOutcome::NonManifold);
    std::size_t used = 1;
    const Index first = link[0].first;
    Index cur = link[0].second;
    std::vector<char> taken(link.size(), 0);
    taken[0] = 1;
    while (cur != first) {
      bool found = false;
      for (std::size_t i = 0; i < link.size(); ++i) {
        if (taken[i]) continue;
        if (link[i].first == cur || link[i].second == cur) {
          cur = link[i].first == cur ? link[i].second : link[i].first;
          taken[i] = 1;
          ++used;
          found = true;
          break;
        }
      }
      if (!found) return rollback(CarveOutcome::NonManifold);
    }
    if (used != link.size()) return rollback(CarveOutcome::NonManifold);
  }
  if (options.preserve_topology && euler() != chi_before) return rollback(CarveOutcome::TopologyChange);

  // Commit. The region must close against kept cells (D not empty).
  bool closes = false;
  for (CellId c : region)
    for (int k = 0; k < 4 && !closes; ++k) closes = d.solid(d.neighbour(c, k));
  if (!closes) return rollback(CarveOutcome::NotSeparated);
  // Vertices that left the surface, and those whose witness was carved, get a new witness: the
  // path ball that covers them best.
  std::vector<Index> to_attach;
  for (Index v : verts)
    if (!d.on_surface(v)) {
      to_attach.push_back(v);
      ++report.removed_vertices;
    }
  for (CellId c : region) {
    const auto it = attached.find(c);
    if (it == attached.end()) continue;
    to_attach.insert(to_attach.end(), it->second.begin(), it->second.end());
    attached.erase(it);
  }
  for (Index v : to_attach) {
    std::size_t best = 0;
    double best_excess = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < balls.size(); ++i) {
      const double excess = (d.point(v) - balls[i].centre).norm() - balls[i].radius;
      if (excess < best_excess) {
        best_excess = excess;
        best = i;
      }
    }
    attached[path[best]].push_back(v);
    witness[v] = path[best];
  }
  return CarveOutcome::Removed;
}

}  // namespace medax::durix
