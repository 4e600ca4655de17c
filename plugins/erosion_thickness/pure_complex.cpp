#include "pure_complex.hpp"

#include <medax/services/kdtree.hpp>
#include <medax/union_find.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace medax::et {

PureComplexReport make_pure_complex(MedialComplex& mc, double weld_tolerance) {
  PureComplexReport report;
  const std::size_t nv = mc.num_vertices();

  // 1. Weld: representative = lowest index of each cluster (UnionFind's rule).
  UnionFind weld(nv);
  if (weld_tolerance > 0 && nv > 1) {
    const services::PointIndex index(mc.centres);
    for (Index i = 0; i < nv; ++i)
      for (const auto& [j, d] : index.within(mc.centres[i], weld_tolerance))
        if (j != i) weld.unite(i, j);
  } else {
    std::vector<Index> order(nv);
    std::iota(order.begin(), order.end(), Index(0));
    auto less = [&](Index a, Index b) {
      const Vec3 &p = mc.centres[a], &q = mc.centres[b];
      return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t k = 1; k < order.size(); ++k)
      if (mc.centres[order[k]] == mc.centres[order[k - 1]]) weld.unite(order[k - 1], order[k]);
  }
  for (Index i = 0; i < nv; ++i) {
    const Index r = weld.find(i);
    if (r != i) {
      ++report.welded_vertices;
      report.max_weld_radius_gap = std::max(report.max_weld_radius_gap, std::abs(mc.radii[i] - mc.radii[r]));
      if (mc.generators.size() == nv) {
        auto& g = mc.generators[r];
        g.insert(g.end(), mc.generators[i].begin(), mc.generators[i].end());
      }
    }
  }

  // 2. Faces: on the welded vertices (rewritten in place), drop degenerate and duplicates.
  std::vector<Index> keep_faces;
  {
    std::vector<std::pair<Tri, Index>> keys;  // sorted corners, face index
    for (Index f = 0; f < mc.faces.size(); ++f) {
      Tri t = {weld.find(mc.faces[f][0]), weld.find(mc.faces[f][1]), weld.find(mc.faces[f][2])};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        ++report.degenerate_faces;
        continue;
      }
      Tri s = t;
      std::sort(s.begin(), s.end());
      keys.push_back({s, f});
    }
    std::sort(keys.begin(), keys.end());
    std::vector<char> keep(mc.faces.size(), 0);
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (k > 0 && keys[k].first == keys[k - 1].first) {
        ++report.duplicate_faces;
        continue;
      }
      keep[keys[k].second] = 1;
    }
    for (Index f = 0; f < mc.faces.size(); ++f)
      if (keep[f]) {
        keep_faces.push_back(f);
        for (Index& v : mc.faces[f]) v = weld.find(v);
      }
  }

  // 3. Dangling edges: listed edges that are no side of a kept face.
  {
    std::vector<std::uint64_t> sides;
    for (Index f : keep_faces)
      for (int j = 0; j < 3; ++j) {
        const Tri& t = mc.faces[f];
        const Index a = std::min(t[j], t[(j + 1) % 3]), b = std::max(t[j], t[(j + 1) % 3]);
        sides.push_back((std::uint64_t(a) << 32) | b);
      }
    std::sort(sides.begin(), sides.end());
    std::vector<std::uint64_t> listed;
    for (const Segment& e : mc.edges) {
      const Index a = weld.find(e[0]), b = weld.find(e[1]);
      if (a == b) continue;
      listed.push_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
    for (std::uint64_t k : listed)
      if (!std::binary_search(sides.begin(), sides.end(), k)) ++report.dangling_edges;
  }

  // 4. Vertices on some kept face.
  std::vector<char> used(nv, 0);
  for (Index f : keep_faces)
    for (Index v : mc.faces[f]) used[v] = 1;
  std::vector<Index> keep_vertices;
  for (Index v = 0; v < nv; ++v)
    if (used[v]) keep_vertices.push_back(v);
    else if (weld.find(v) == v) ++report.isolated_vertices;

  // 5. The kept vertices and faces with every column (kernel subcomplex), each survivor with
  // the generators of its cluster; edges rebuilt as the faces' sides, without the old edge
  // columns.
  if (!mc.generators.empty())
    for (Index v : keep_vertices) {
      auto& g = mc.generators[v];
      std::sort(g.begin(), g.end());
      g.erase(std::unique(g.begin(), g.end()), g.end());
    }
  MedialComplex out = mc.subcomplex(keep_vertices, {}, keep_faces);
  out.edge_props = {};
  out.close_edges();
  mc = std::move(out);
  return report;
}

}  // namespace medax::et
