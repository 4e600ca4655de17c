// Sheets (paper §4.3) and singular / boundary half-paths (paper §4.4, Algorithm 2 as corrected
// in notes §3.4: the candidate next(h) is itself tested).
#include "engine.hpp"

#include <algorithm>
#include <map>
#include <unordered_set>

namespace medax::durix {

namespace {
constexpr std::size_t kMaxRotation = 1u << 12;  // half-edges around one node on one side
}

std::size_t Engine::label_sheet(EdgeId e0, int label, std::deque<HalfEdge>* queue) {
  if (!d.volumetric(e0) || d.label(e0) >= 0) return 0;
  std::deque<EdgeId> todo{e0};
  d.set_label(e0, label);
  std::size_t count = 1;
  std::vector<Facet> facets;
  while (!todo.empty()) {
    const EdgeId e = todo.front();
    todo.pop_front();
    const Index a = d.edge_vertices(e)[0], b = d.edge_vertices(e)[1];
    d.ring_facets(e, facets);
    for (const Facet& t : facets) {
      const int deg = d.degree(t);
      const bool forced = d.forced(t);
      if (deg == 2 && !forced) {
        const auto fv = d.facet_vertices(t);
        const Index w = fv[0] != a && fv[0] != b ? fv[0] : fv[1] != a && fv[1] != b ? fv[1] : fv[2];
        const EdgeId ea = d.edge_of(t.cell, a, w), eb = d.edge_of(t.cell, b, w);
        const EdgeId other = d.volumetric(ea) ? ea : eb;
        if (d.label(other) < 0) {
          d.set_label(other, label);
          todo.push_back(other);
          ++count;
        }
      } else if ((deg >= 3 || forced) && queue) {
        queue->push_back({t, a, b});
        queue->push_back({t, b, a});
      }
    }
  }
  return count;
}

bool Engine::singular(const HalfEdge& h) const {
  if (d.degree(h.t) < 3 && !d.forced(h.t)) return false;
  const EdgeId e = d.face(h);
  if (!d.volumetric(e)) return false;
  const int l = d.label(e);
  if (l < 0) return true;
  return d.label(d.face(d.side_nbr(h))) != l;
}

bool Engine::boundary_half_edge(const HalfEdge& h) const {
  return d.degree(h.t) == 1 && d.volumetric(d.face(h));
}

namespace {

template <typename Pred>
HalfPath follow_path(const Dual& d, const HalfEdge& h0, const Pred& on_path) {
  HalfPath path;
  path.edges.push_back(h0);
  path.corners.push_back(h0.u);
  std::unordered_set<HalfEdge, HalfEdgeHash> seen{h0};
  HalfEdge h = d.next(h0);
  for (;;) {
    std::size_t rotation = 0;
    while (!on_path(h)) {
      // Rotate around start(h) on the same side: to the neighbouring face, then along it. The
      // corner changes exactly where the rotation crosses an open face, i.e. a surface edge.
      HalfEdge g = d.cell_nbr(h);
      for (int i = 0; i < 3 && !d.volumetric(d.face(g)); ++i) {
        // Crossing the open face of g, a surface edge: the corner moves along it.
        g = d.cell_nbr(d.flip(g));
        if (!d.surface_edge(d.edge_of(h.t.cell, path.corners.back(), g.u))) ++path.corner_errors;
        path.corners.push_back(g.u);
      }
      h = d.next(g);
      if (++rotation > kMaxRotation) return path;  // not closed
    }
    if (h == h0) {
      path.closed = true;
      return path;
    }
    if (!seen.insert(h).second) return path;  // a lasso: the walk does not come back to h0
    path.edges.push_back(h);
    h = d.next(h);
  }
}

}  // namespace

HalfPath Engine::follow(const HalfEdge& h0) const {
  return follow_path(d, h0, [this](const HalfEdge& h) { return singular(h); });
}

HalfPath Engine::follow_boundary(const HalfEdge& h0) const {
  return follow_path(d, h0, [this](const HalfEdge& h) { return boundary_half_edge(h); });
}

void Engine::census_paths() {
  std::unordered_set<HalfEdge, HalfEdgeHash> visited;
  std::map<Facet, int> boundary_uses;
  std::size_t boundary_edges = 0;
  d.for_each_solid_facet([&](const Facet& t) {
    const int deg = d.degree(t);
    if (deg == 1) ++boundary_edges;
    if (deg == 0 || (deg == 2 && !d.forced(t))) return;
    const bool boundary = deg == 1;
    d.for_each_half_edge(t, [&](const HalfEdge& h) {
      if (visited.count(h) || (boundary ? !boundary_half_edge(h) : !singular(h))) return;
      const HalfPath path = boundary ? follow_boundary(h) : follow(h);
      (boundary ? report.boundary_paths : report.singular_paths) += 1;
      if (!path.closed) ++report.unclosed_paths;
      report.loop_corner_errors += path.corner_errors;
      for (const HalfEdge& p : path.edges) {
        visited.insert(p);
        if (boundary) ++boundary_uses[p.t];
      }
    });
  });
  for (const auto& [t, uses] : boundary_uses) report.boundary_multiplicity_errors += uses != 2;
  if (boundary_uses.size() != boundary_edges)
    report.boundary_multiplicity_errors += boundary_edges - std::min(boundary_edges, boundary_uses.size());
}

std::vector<CellId> Engine::path_nodes(const HalfPath& path) const {
  std::vector<CellId> nodes;
  nodes.reserve(path.edges.size() * 2);
  for (const HalfEdge& h : path.edges) {
    nodes.push_back(h.t.cell);
    nodes.push_back(d.other_cell(h.t));
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace medax::durix
