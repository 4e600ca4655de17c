// Problematic edges (paper §4.7, Algorithm 3; notes §3.8): a degree-3 medial edge whose three
// faces carry the same sheet label. Each chain of problematic edges is extended from its free
// end (the end not on the sheet's boundary) to the nearest boundary node of the sheet by a
// shortest path (Dijkstra on centre distances) over the sheet's regular edges; those edges are
// forced singular and the sheet is relabelled, which splits it. Whatever remains (chains closed
// on themselves, or with no free end) is resolved by cutting off the edge's fin by competing
// fronts (split_fin), so the check "no edge has three faces of one sheet" holds.
#include "engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

namespace medax::durix {

namespace {

/// The volumetric faces (DT edges) of a facet.
int facet_faces(const Dual& d, const Facet& t, EdgeId out[3]) {
  const auto v = d.facet_vertices(t);
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const EdgeId e = d.edge_of(t.cell, v[i], v[(i + 1) % 3]);
    if (d.volumetric(e)) out[n++] = e;
  }
  return n;
}

/// The two faces of a regular medial edge that a cut may force (degree 2, not forced yet);
/// false for any other facet.
bool regular_faces(const Dual& d, const Facet& t, EdgeId out[3]) {
  return d.is_medial_edge(t) && d.degree(t) == 2 && !d.forced(t) && facet_faces(d, t, out) == 2;
}

/// The sheet label of a medial edge's faces (the first face's).
int sheet_label(const Dual& d, const Facet& t) {
  EdgeId faces[3];
  facet_faces(d, t, faces);
  return d.label(faces[0]);
}

/// A regular edge of sheet `label` usable by a cut: degree 2, not forced, both faces on it.
bool regular_in(const Dual& d, const Facet& t, int label) {
  EdgeId f[3];
  return regular_faces(d, t, f) && d.label(f[0]) == label && d.label(f[1]) == label;
}

/// True when node c lies on the boundary of sheet `label` (has a degree-1 edge of that sheet).
bool on_sheet_boundary(const Dual& d, CellId c, int label) {
  for (int k = 0; k < 4; ++k) {
    const Facet t = d.facet(c, k);
    if (d.is_medial_edge(t) && d.degree(t) == 1 && sheet_label(d, t) == label) return true;
  }
  return false;
}

/// The face at a problematic edge whose plane is least parallel to the other two (a Voronoi
/// face lies in the bisector plane of its DT edge); the other two continue the sheet.
int fin_face(const Dual& d, const EdgeId faces[3]) {
  const auto normal = [&](EdgeId f) {
    const auto v = d.edge_vertices(f);
    return (d.point(v[1]) - d.point(v[0])).normalized();
  };
  int fin = 0;
  double most_parallel = -1;
  for (int i = 0; i < 3; ++i) {
    const double p = std::abs(normal(faces[(i + 1) % 3]).dot(normal(faces[(i + 2) % 3])));
    if (p > most_parallel) most_parallel = p, fin = i;
  }
  return fin;
}

/// Free ends of the chains of problematic edges of one sheet: chain endpoints (nodes met by one
/// problematic edge) not on the sheet's boundary.
std::vector<CellId> free_chain_ends(const Dual& d, const std::vector<Facet>& chain_edges, int label) {
  std::map<CellId, int> chain_degree;
  for (const Facet& f : chain_edges) {
    ++chain_degree[f.cell];
    ++chain_degree[d.other_cell(f)];
  }
  std::vector<CellId> free_ends;
  for (const auto& [node, degree] : chain_degree)
    if (degree == 1 && !on_sheet_boundary(d, node, label)) free_ends.push_back(node);
  return free_ends;
}

}  // namespace

bool Engine::problematic(const Facet& f) const {
  if (!d.is_medial_edge(f) || d.degree(f) != 3) return false;
  EdgeId faces[3];
  facet_faces(d, f, faces);
  const int l = d.label(faces[0]);
  return l >= 0 && d.label(faces[1]) == l && d.label(faces[2]) == l;
}

void Engine::FinScratch::prepare(std::size_t num_edges) {
  if (stamp.size() != num_edges) {
    stamp.assign(num_edges, 0);
    best.assign(num_edges, 0);
    settled.assign(num_edges, 0);
    centroid.assign(num_edges, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
    current = 0;
  }
  ++current;  // faces whose stamp differs were not reached in this call
}

const Vec3& Engine::face_centroid(EdgeId f, FinScratch& z) const {
  Vec3& c = z.centroid[f];
  if (std::isnan(c.x())) {
    d.ring(f, z.ring);
    c = Vec3::Zero();
    for (CellId cell : z.ring) c += d.centre(cell);
    c /= double(z.ring.size());
  }
  return c;
}

std::vector<EdgeId> Engine::fin_region(const EdgeId faces[3], int fin, FinScratch& z) const {
  const int label = d.label(faces[0]);
  struct Entry {
    double distance;
    EdgeId face;
    bool fin;
    bool operator>(const Entry& o) const { return distance != o.distance ? distance > o.distance : face > o.face; }
  };
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  std::size_t fin_entries = 0;
  std::vector<EdgeId> region;
  // settled: 0 open, 1 the fin's region, 2 the rest.
  const auto push = [&](double distance, EdgeId f, bool is_fin) {
    if (z.stamp[f] == z.current && (z.settled[f] != 0 || z.best[f] <= distance)) return;
    if (z.stamp[f] != z.current) z.settled[f] = 0;
    z.stamp[f] = z.current;
    z.best[f] = distance;
    heap.push({distance, f, is_fin});
    fin_entries += is_fin;
  };
  for (int i = 0; i < 3; ++i) push(0, faces[i], i == fin);
  while (!heap.empty() && fin_entries > 0) {
    const Entry top = heap.top();
    heap.pop();
    fin_entries -= top.fin;
    if (z.settled[top.face] != 0 || z.best[top.face] < top.distance) continue;
    z.settled[top.face] = top.fin ? 1 : 2;
    if (top.fin) region.push_back(top.face);
    const Vec3 from = face_centroid(top.face, z);
    d.ring_facets(top.face, z.facets);
    for (const Facet& t : z.facets) {
      const EdgeId next = face_across(t, top.face);
      if (next != kNoId && d.label(next) == label) push(top.distance + (face_centroid(next, z) - from).norm(), next, top.fin);
    }
  }
  return region;
}

EdgeId Engine::face_across(const Facet& t, EdgeId f) const {
  EdgeId pair[3];
  if (!regular_faces(d, t, pair)) return kNoId;
  return pair[0] == f ? pair[1] : pair[0];
}

void Engine::split_fin(const Facet& edge, FinScratch& z) {
  // Fronts grow from the fin and from the two other faces at once over the sheet's regular
  // edges (Dijkstra on polygon centroid distances); a face belongs to the front that reaches it
  // first, and the growth stops when the fin's front is spent. The regular edges between the
  // fin's region and the rest become forced singular, and the region gets a new label.
  EdgeId faces[3];
  facet_faces(d, edge, faces);
  z.prepare(d.num_edges());
  const std::vector<EdgeId> region = fin_region(faces, fin_face(d, faces), z);
  const int fin_label = next_label++;
  for (EdgeId f : region) {
    d.set_label(f, fin_label);
    d.ring_facets(f, z.facets);
    for (const Facet& t : z.facets) {
      const EdgeId other = face_across(t, f);
      if (other == kNoId || (z.stamp[other] == z.current && z.settled[other] == 1)) continue;
      d.set_forced(t, true);
      ++report.forced_edges;
    }
  }
}

std::vector<Facet> Engine::problematic_edges() const {
  std::vector<Facet> out;
  d.for_each_solid_facet([&](const Facet& f) {
    if (problematic(f)) out.push_back(f);
  });
  return out;
}

void Engine::relabel_sheets(const std::vector<int>& labels) {
  if (labels.empty()) return;
  std::map<int, std::vector<EdgeId>> faces;
  for (int l : labels) faces[l];
  for (EdgeId e = 0; e < d.num_edges(); ++e) {
    if (!d.volumetric(e)) continue;
    const auto it = faces.find(d.label(e));
    if (it != faces.end()) it->second.push_back(e);
  }
  for (auto& [label, list] : faces) {
    for (EdgeId e : list) d.set_label(e, -1);
    bool first = true;
    for (EdgeId e : list)
      if (d.label(e) < 0) {
        label_sheet(e, first ? label : next_label++, nullptr);
        first = false;
      }
  }
}

bool Engine::cut_to_sheet_boundary(CellId start, int label) {
  std::map<CellId, double> dist;
  std::map<CellId, Facet> via;
  using Item = std::pair<double, CellId>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  dist[start] = 0;
  heap.push({0, start});
  CellId target = kNoId;
  std::size_t visited = 0;
  while (!heap.empty() && visited < 200000) {
    const auto [dc, c] = heap.top();
    heap.pop();
    if (dc > dist[c]) continue;
    ++visited;
    if (c != start && on_sheet_boundary(d, c, label)) {
      target = c;
      break;
    }
    for (int k = 0; k < 4; ++k) {
      const Facet t = d.facet(c, k);
      if (!regular_in(d, t, label)) continue;
      const CellId n = d.neighbour(c, k);
      const double nd = dc + (d.centre(n) - d.centre(c)).norm();
      const auto it = dist.find(n);
      if (it == dist.end() || nd < it->second) {
        dist[n] = nd;
        via[n] = t;
        heap.push({nd, n});
      }
    }
  }
  if (target == kNoId) return false;
  for (CellId c = target; c != start;) {
    const Facet t = via.at(c);
    d.set_forced(t, true);
    ++report.forced_edges;
    c = t.cell == c ? d.other_cell(t) : t.cell;
  }
  return true;
}

std::vector<Facet> Engine::cut_chains(std::vector<Facet> found) {
  for (int round = 0; round < 32 && !found.empty(); ++round) {
    if (check_cancelled) check_cancelled();
    bool progress = false;
    std::map<int, std::vector<Facet>> by_label;
    for (const Facet& f : found) by_label[sheet_label(d, f)].push_back(f);
    for (const auto& [label, chain_edges] : by_label)
      for (CellId start : free_chain_ends(d, chain_edges, label)) progress |= cut_to_sheet_boundary(start, label);
    std::vector<int> labels;
    for (const auto& entry : by_label) labels.push_back(entry.first);
    relabel_sheets(labels);
    std::vector<Facet> again = problematic_edges();
    const bool stalled = !progress || again.size() >= found.size();
    found = std::move(again);
    if (stalled) break;
  }
  return found;
}

std::vector<Facet> Engine::split_fins(std::vector<Facet> found) {
  FinScratch fin_scratch;
  for (int round = 0; round < 100 && !found.empty(); ++round) {
    if (check_cancelled) check_cancelled();
    std::vector<int> labels;
    for (const Facet& f : found) {
      if (!problematic(f)) continue;
      labels.push_back(sheet_label(d, f));
      split_fin(f, fin_scratch);
    }
    sort_unique(labels);
    relabel_sheets(labels);
    found = problematic_edges();
  }
  return found;
}

void Engine::split_problematic() {
  std::vector<Facet> found = problematic_edges();
  report.problematic_edges = found.size();
  found = cut_chains(std::move(found));
  // Fallback: whatever remains is split by competing fronts, all edges of a round at once.
  report.problematic_left = split_fins(std::move(found)).size();
}

}  // namespace medax::durix
