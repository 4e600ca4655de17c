#include "pure_complex.hpp"

#include <medax/services/kdtree.hpp>
#include <medax/union_find.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace medax::et {

namespace {

/// Clusters of centres within the tolerance (exactly equal ones when it is 0); the
/// representative is the lowest index of each cluster (UnionFind's rule).
UnionFind weld_clusters(const MedialComplex& mc, double weld_tolerance) {
  const std::size_t nv = mc.num_vertices();
  UnionFind weld(nv);
  if (weld_tolerance > 0 && nv > 1) {
    const services::PointIndex index(mc.centres);
    for (Index i = 0; i < nv; ++i)
      for (const auto& [j, d] : index.within(mc.centres[i], weld_tolerance))
        if (j != i) weld.unite(i, j);
    return weld;
  }
  std::vector<Index> order(nv);
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    const Vec3 &p = mc.centres[a], &q = mc.centres[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
  });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (mc.centres[order[k]] == mc.centres[order[k - 1]]) weld.unite(order[k - 1], order[k]);
  return weld;
}

/// Gives each representative its cluster's generators; counts the welded vertices.
void merge_welded(MedialComplex& mc, UnionFind& weld, PureComplexReport& report) {
  const std::size_t nv = mc.num_vertices();
  for (Index i = 0; i < nv; ++i) {
    const Index r = weld.find(i);
    if (r == i) continue;
    ++report.welded_vertices;
    report.max_weld_radius_gap = std::max(report.max_weld_radius_gap, std::abs(mc.radii[i] - mc.radii[r]));
    if (mc.generators.size() == nv) {
      auto& g = mc.generators[r];
      g.insert(g.end(), mc.generators[i].begin(), mc.generators[i].end());
    }
  }
}

/// The faces kept on the welded vertices (rewritten in place): neither degenerate nor a
/// duplicate of an earlier face.
std::vector<Index> kept_faces(MedialComplex& mc, UnionFind& weld, PureComplexReport& report) {
  std::vector<std::pair<Tri, Index>> keys;  // sorted corners, face index
  for (Index f = 0; f < mc.faces.size(); ++f) {
    Tri t = {weld.find(mc.faces[f][0]), weld.find(mc.faces[f][1]), weld.find(mc.faces[f][2])};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++report.degenerate_faces;
      continue;
    }
    std::sort(t.begin(), t.end());
    keys.push_back({t, f});
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> keep(mc.faces.size(), 0);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (k > 0 && keys[k].first == keys[k - 1].first) ++report.duplicate_faces;
    else keep[keys[k].second] = 1;
  }
  std::vector<Index> faces;
  for (Index f = 0; f < mc.faces.size(); ++f)
    if (keep[f]) {
      faces.push_back(f);
      for (Index& v : mc.faces[f]) v = weld.find(v);
    }
  return faces;
}

std::uint64_t edge_key(Index a, Index b) { return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b); }

/// Listed edges (on welded vertices) that are no side of a kept face.
std::size_t dangling_edges(const MedialComplex& mc, UnionFind& weld, const std::vector<Index>& faces) {
  std::vector<std::uint64_t> sides;
  for (Index f : faces)
    for (int j = 0; j < 3; ++j) sides.push_back(edge_key(mc.faces[f][j], mc.faces[f][(j + 1) % 3]));
  std::sort(sides.begin(), sides.end());
  std::vector<std::uint64_t> listed;
  for (const Segment& e : mc.edges) {
    const Index a = weld.find(e[0]), b = weld.find(e[1]);
    if (a != b) listed.push_back(edge_key(a, b));
  }
  std::sort(listed.begin(), listed.end());
  listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
  return std::count_if(listed.begin(), listed.end(),
                       [&](std::uint64_t k) { return !std::binary_search(sides.begin(), sides.end(), k); });
}

/// Vertices on some kept face; counts the representatives on none.
std::vector<Index> kept_vertices(const MedialComplex& mc, UnionFind& weld, const std::vector<Index>& faces,
                                 PureComplexReport& report) {
  std::vector<char> used(mc.num_vertices(), 0);
  for (Index f : faces)
    for (Index v : mc.faces[f]) used[v] = 1;
  std::vector<Index> vertices;
  for (Index v = 0; v < mc.num_vertices(); ++v)
    if (used[v]) vertices.push_back(v);
    else if (weld.find(v) == v) ++report.isolated_vertices;
  return vertices;
}

}  // namespace

PureComplexReport make_pure_complex(MedialComplex& mc, double weld_tolerance) {
  PureComplexReport report;
  UnionFind weld = weld_clusters(mc, weld_tolerance);
  merge_welded(mc, weld, report);
  const std::vector<Index> faces = kept_faces(mc, weld, report);
  report.dangling_edges += dangling_edges(mc, weld, faces);
  const std::vector<Index> vertices = kept_vertices(mc, weld, faces, report);
  // The kept vertices and faces with every column (kernel subcomplex), each survivor with the
  // generators of its cluster; edges rebuilt as the faces' sides, without the old edge columns.
  if (!mc.generators.empty())
    for (Index v : vertices) {
      auto& g = mc.generators[v];
      std::sort(g.begin(), g.end());
      g.erase(std::unique(g.begin(), g.end()), g.end());
    }
  MedialComplex out = mc.subcomplex(vertices, {}, faces);
  out.edge_props = {};
  out.close_edges();
  mc = std::move(out);
  return report;
}

}  // namespace medax::et
