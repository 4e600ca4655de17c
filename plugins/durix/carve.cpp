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
#include <limits>
#include <optional>
#include <stdexcept>

namespace medax::durix {

namespace {

/// The elements whose surface status a carving of `region` may change.
struct Affected {
  std::vector<EdgeId> edges;
  std::vector<Facet> facets;
  std::vector<Index> verts;
};

Affected affected_elements(const Dual& d, const std::vector<CellId>& region) {
  Affected a;
  for (CellId c : region) {
    for (int p = 0; p < 6; ++p) a.edges.push_back(d.cell_edge(c, p));
    for (int k = 0; k < 4; ++k) a.facets.push_back(d.facet(c, k));
    for (Index v : d.cell(c)) a.verts.push_back(v);
  }
  sort_unique(a.edges);
  sort_unique(a.facets);
  sort_unique(a.verts);
  return a;
}

/// The affected elements' share of M_w's Euler characteristic (V − E + F of its surface).
long long surface_euler(const Dual& d, const Affected& a) {
  long long chi = 0;
  for (Index v : a.verts) chi += d.on_surface(v);
  for (EdgeId e : a.edges) chi -= d.surface_edge(e);
  for (const Facet& f : a.facets) chi += d.is_surface_facet(f);
  return chi;
}

/// Edge-manifold: every edge has 0 or 2 surface facets around it.
bool edges_manifold(const Dual& d, const std::vector<EdgeId>& edges) {
  std::vector<CellId> ring;
  for (EdgeId e : edges) {
    if (d.solid_count_of(e) == 0) continue;
    d.ring(e, ring);
    std::size_t transitions = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) transitions += d.solid(ring[i]) != d.solid(ring[(i + 1) % ring.size()]);
    if (transitions != 0 && transitions != 2) return false;
  }
  return true;
}

using Segment = std::pair<Index, Index>;

/// The link of surface vertex v: the edge opposite v of each surface facet around it.
void surface_link(const Dual& d, Index v, std::vector<Segment>& link) {
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
}

/// True when the segments form one cycle: the walk from the first segment uses every one once.
bool one_cycle(const std::vector<Segment>& link) {
  if (link.size() < 3) return false;
  std::vector<char> taken(link.size(), 0);
  taken[0] = 1;
  std::size_t used = 1;
  const Index first = link[0].first;
  Index cur = link[0].second;
  while (cur != first) {
    const auto next = std::find_if(link.begin(), link.end(), [&](const Segment& s) {
      return !taken[&s - link.data()] && (s.first == cur || s.second == cur);
    });
    if (next == link.end()) return false;
    taken[next - link.begin()] = 1;
    cur = next->first == cur ? next->second : next->first;
    ++used;
  }
  return used == link.size();
}

/// Vertex-manifold: the surface facets around each surface vertex form one disk.
bool vertices_manifold(const Dual& d, const std::vector<Index>& verts) {
  std::vector<Segment> link;
  for (Index v : verts) {
    if (!d.on_surface(v)) continue;
    surface_link(d, v, link);
    if (!one_cycle(link)) return false;
  }
  return true;
}

/// The carved region must close against kept cells (D not empty).
bool closes_against_solid(const Dual& d, const std::vector<CellId>& region) {
  for (CellId c : region)
    for (int k = 0; k < 4; ++k)
      if (d.solid(d.neighbour(c, k))) return true;
  return false;
}

/// The index of the ball whose boundary is nearest to p (most negative excess).
std::size_t best_covering_ball(const Vec3& p, const std::vector<Ball>& balls) {
  std::size_t best = 0;
  double best_excess = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < balls.size(); ++i) {
    const double excess = (p - balls[i].centre).norm() - balls[i].radius;
    if (excess < best_excess) {
      best_excess = excess;
      best = i;
    }
  }
  return best;
}

}  // namespace

/// Marks the path's cells and vertices with fresh stamps and returns its balls.
std::vector<Ball> Engine::mark_path(const std::vector<CellId>& path, CarveStamps& stamps) {
  if (stamp > std::numeric_limits<std::uint32_t>::max() - 8) {
    std::fill(cell_mark.begin(), cell_mark.end(), 0);
    std::fill(vertex_mark.begin(), vertex_mark.end(), 0);
    stamp = 0;
  }
  stamps = {++stamp, ++stamp, ++stamp};
  std::vector<Ball> balls;
  balls.reserve(path.size());
  for (CellId c : path) {
    cell_mark[c] = stamps.path;
    balls.push_back({d.centre(c), d.radius(c)});
    for (Index v : d.cell(c)) vertex_mark[v] = stamps.vertex;  // on the path's spheres
  }
  return balls;
}

std::optional<CarveOutcome> Engine::flood_region(const std::vector<CellId>& seeds, const std::vector<Ball>& balls,
                                                 const CarveStamps& stamps, const FloodRules& rules,
                                                 std::vector<CellId>& region) {
  std::size_t hint = 0;
  const auto covered = [&](Index v) { return !rules.test_coverage || oracle.covered(d.point(v), balls, hint); };
  const auto enter = [&](CellId c) {
    if (!d.solid(c) || cell_mark[c] == stamps.path || cell_mark[c] == stamps.region) return;
    cell_mark[c] = stamps.region;
    region.push_back(c);
  };
  for (CellId s : seeds) enter(s);
  if (region.empty()) return CarveOutcome::NotSeparated;
  for (std::size_t i = 0; i < region.size(); ++i) {
    const CellId c = region[i];
    if ((i & 4095) == 4095 && check_cancelled) check_cancelled();
    if (rules.stop_at_labels)
      for (int p = 0; p < 6; ++p) {
        const EdgeId e = d.cell_edge(c, p);
        if (d.volumetric(e) && d.label(e) >= 0) return CarveOutcome::NotSeparated;
      }
    for (Index v : d.cell(c))
      if (vertex_mark[v] != stamps.vertex) {
        vertex_mark[v] = stamps.vertex;
        if (!covered(v)) return CarveOutcome::Significant;
      }
    if (const auto it = attached.find(c); it != attached.end())
      for (Index v : it->second)
        if (!covered(v)) return CarveOutcome::Significant;
    for (int k = 0; k < 4; ++k) enter(d.neighbour(c, k));
  }
  return std::nullopt;
}

/// Vertices that left the surface, and those whose witness was carved, get a new witness: the
/// path ball that covers them best.
void Engine::reattach_witnesses(const std::vector<CellId>& path, const std::vector<Ball>& balls,
                                const std::vector<CellId>& region, const std::vector<Index>& verts) {
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
    const CellId cell = path[best_covering_ball(d.point(v), balls)];
    attached[cell].push_back(v);
    witness[v] = cell;
  }
}

void Engine::set_region_solid(const std::vector<CellId>& region, bool solid) {
  static const bool debug = std::getenv("MEDAX_DURIX_DEBUG") != nullptr;
  for (CellId c : region) d.set_solid(c, solid);
  if (debug && d.verify_counters()) throw std::logic_error("Durix: surface counters broken by a carving");
}

CarveOutcome Engine::carve(const std::vector<CellId>& path, const std::vector<CellId>& seeds, bool stop_at_labels,
                           bool test_coverage) {
  if (test_coverage && oracle.epsilon() <= 0) return CarveOutcome::Significant;
  CarveStamps stamps;
  const std::vector<Ball> balls = mark_path(path, stamps);
  std::vector<CellId> region;
  if (const auto stopped = flood_region(seeds, balls, stamps, {stop_at_labels, test_coverage}, region)) return *stopped;

  const Affected affected = affected_elements(d, region);
  const long long chi_before = surface_euler(d, affected);
  set_region_solid(region, false);
  const auto rollback = [&](CarveOutcome outcome) {
    set_region_solid(region, true);
    return outcome;
  };
  if (!edges_manifold(d, affected.edges) || !vertices_manifold(d, affected.verts))
    return rollback(CarveOutcome::NonManifold);
  if (options.preserve_topology && surface_euler(d, affected) != chi_before)
    return rollback(CarveOutcome::TopologyChange);
  if (!closes_against_solid(d, region)) return rollback(CarveOutcome::NotSeparated);
  reattach_witnesses(path, balls, region, affected.verts);
  return CarveOutcome::Removed;
}

}  // namespace medax::durix
