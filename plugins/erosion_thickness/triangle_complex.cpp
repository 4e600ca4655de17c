#include "triangle_complex.hpp"

#include <medax/union_find.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <stdexcept>
#include <string>

namespace medax::et {

double TriangleComplex::max_bbox_side() const {
  if (points.empty()) return 0.0;
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).maxCoeff();
}

TriangleComplex build_triangle_complex(std::vector<Vec3> points, std::vector<double> radii,
                                       std::vector<Tri> triangles) {
  TriangleComplex cx;
  cx.points = std::move(points);
  cx.radii = std::move(radii);
  cx.triangles = std::move(triangles);
  const std::size_t nv = cx.points.size(), nt = cx.triangles.size();
  if (cx.radii.size() != nv) throw std::invalid_argument("one radius per point");
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& f = cx.triangles[t];
    for (int j = 0; j < 3; ++j)
      if (f[j] >= nv) throw std::invalid_argument(fmt::format("triangle {} has a vertex index out of range", t));
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2])
      throw std::invalid_argument(
          fmt::format("triangle {} repeats a vertex; clean the complex first (`pure_complex`)", t));
  }

  // Unique edges: sort (key, triangle, side) records.
  struct Rec {
    std::uint64_t key;
    Index t;
    int j;
  };
  std::vector<Rec> recs;
  recs.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (int j = 0; j < 3; ++j) {
      const Index a = cx.triangles[t][j], b = cx.triangles[t][(j + 1) % 3];
      const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
      recs.push_back({(lo << 32) | hi, static_cast<Index>(t), j});
    }
  std::sort(recs.begin(), recs.end(),
            [](const Rec& x, const Rec& y) { return x.key < y.key || (x.key == y.key && x.t < y.t); });
  cx.tri_edges.assign(nt, {kNone, kNone, kNone});
  cx.tri_edge_slot.assign(nt, {0, 0, 0});
  cx.edge_tri_begin.push_back(0);
  for (std::size_t i = 0; i < recs.size();) {
    std::size_t k = i;
    const Index e = static_cast<Index>(cx.edges.size());
    cx.edges.push_back({static_cast<Index>(recs[i].key >> 32), static_cast<Index>(recs[i].key & 0xffffffffu)});
    for (; k < recs.size() && recs[k].key == recs[i].key; ++k) {
      cx.tri_edges[recs[k].t][recs[k].j] = e;
      cx.tri_edge_slot[recs[k].t][recs[k].j] = static_cast<Index>(k - i);
      cx.edge_tris.push_back(recs[k].t);
    }
    cx.edge_tri_begin.push_back(static_cast<Index>(cx.edge_tris.size()));
    i = k;
  }

  // Vertex -> triangles.
  cx.vert_tri_begin.assign(nv + 1, 0);
  for (const Tri& f : cx.triangles)
    for (Index v : f) ++cx.vert_tri_begin[v + 1];
  std::partial_sum(cx.vert_tri_begin.begin(), cx.vert_tri_begin.end(), cx.vert_tri_begin.begin());
  cx.vert_tris.resize(3 * nt);
  std::vector<Index> fill(cx.vert_tri_begin.begin(), cx.vert_tri_begin.end() - 1);
  for (std::size_t t = 0; t < nt; ++t)
    for (Index v : cx.triangles[t]) cx.vert_tris[fill[v]++] = static_cast<Index>(t);
  return cx;
}

namespace {

/// The link of one vertex, rebuilt for each vertex in reused buffers. A triangle at the vertex
/// has two edges there (its link sides); triangles sharing a manifold edge (degree 2) are in
/// one sector; the link nodes H_v are the edges of degree ≠ 2, and each sector is a chain
/// between two of them (or a closed chain: a self-loop on a node of its own).
struct VertexLink {
  struct Side {
    Index edge;
    int local;  // the triangle's position among the vertex's triangles
  };
  std::vector<Side> sides;
  std::vector<int> sector_of_local, root_to_sector;
  std::vector<int> ends_count;
  std::vector<std::array<int, 2>> ends;
  std::vector<Index> h_edge_ids;
};

int corner_of(const Tri& f, Index v) { return f[0] == v ? 0 : f[1] == v ? 1 : 2; }

/// The link sides of v's `deg` triangles, sorted by edge (then triangle).
void gather_sides(const TriangleComplex& cx, Index v, VertexLink& link) {
  const Index begin = cx.vert_tri_begin[v], deg = cx.vert_tri_begin[v + 1] - begin;
  link.sides.clear();
  for (Index i = 0; i < deg; ++i) {
    const Index t = cx.vert_tris[begin + i];
    const int j = corner_of(cx.triangles[t], v);
    link.sides.push_back({cx.tri_edges[t][j], static_cast<int>(i)});
    link.sides.push_back({cx.tri_edges[t][(j + 2) % 3], static_cast<int>(i)});
  }
  std::sort(link.sides.begin(), link.sides.end(), [](const VertexLink::Side& a, const VertexLink::Side& b) {
    return a.edge < b.edge || (a.edge == b.edge && a.local < b.local);
  });
}

/// Numbers the sectors in order of their first triangle; returns their count.
int number_sectors(const TriangleComplex& cx, Index v, Index deg, VertexLink& link) {
  UnionFind uf(deg);
  for (std::size_t i = 0; i + 1 < link.sides.size(); ++i)
    if (link.sides[i].edge == link.sides[i + 1].edge && cx.edge_degree(link.sides[i].edge) == 2)
      uf.unite(static_cast<Index>(link.sides[i].local), static_cast<Index>(link.sides[i + 1].local));
  link.root_to_sector.assign(deg, -1);
  link.sector_of_local.assign(deg, -1);
  int ns = 0;
  for (Index i = 0; i < deg; ++i) {
    const Index r = uf.find(i);
    if (link.root_to_sector[r] < 0) link.root_to_sector[r] = ns++;
    link.sector_of_local[i] = link.root_to_sector[r];
  }
  if (ns > 0xfffe) throw std::runtime_error(fmt::format("vertex {} has too many sectors", v));
  return ns;
}

/// The H_v nodes (link nodes of degree ≠ 2, in edge order) and each sector's two ends; returns
/// the node count.
int link_nodes(const TriangleComplex& cx, Index v, int ns, VertexLink& link) {
  link.h_edge_ids.clear();
  link.ends_count.assign(ns, 0);
  link.ends.assign(ns, {-1, -1});
  for (const VertexLink::Side& side : link.sides) {
    if (cx.edge_degree(side.edge) == 2) continue;
    if (link.h_edge_ids.empty() || link.h_edge_ids.back() != side.edge) link.h_edge_ids.push_back(side.edge);
    const int node = static_cast<int>(link.h_edge_ids.size()) - 1;
    const int s = link.sector_of_local[side.local];
    if (link.ends_count[s] < 2) link.ends[s][link.ends_count[s]] = node;
    ++link.ends_count[s];
  }
  int nh = static_cast<int>(link.h_edge_ids.size());
  for (int s = 0; s < ns; ++s) {
    if (link.ends_count[s] == 0) link.ends[s] = {nh, nh}, ++nh;  // closed chain: a self-loop on its own node
    else if (link.ends_count[s] == 1) link.ends[s][1] = link.ends[s][0];  // cannot happen for chains; be safe
  }
  if (nh > 0xfffe) throw std::runtime_error(fmt::format("vertex {} has too many link nodes", v));
  return nh;
}

/// ∂G: v is on the boundary when H_v (nodes, sectors as edges) is a forest.
bool link_is_forest(const VertexLink& link, int ns, int nh) {
  UnionFind huf(static_cast<std::size_t>(nh));
  for (int s = 0; s < ns; ++s)
    if (!huf.unite(static_cast<Index>(link.ends[s][0]), static_cast<Index>(link.ends[s][1]))) return false;
  return true;
}

}  // namespace

VertexSectors compute_vertex_sectors(const TriangleComplex& cx) {
  const std::size_t nv = cx.num_vertices(), nt = cx.num_triangles();
  VertexSectors vs;
  vs.corner_sector.assign(3 * nt, 0);
  vs.sector_begin.assign(nv + 1, 0);
  vs.h_nodes.assign(nv, 0);
  vs.boundary.assign(nv, 0);
  VertexLink link;
  for (Index v = 0; v < nv; ++v) {
    const Index begin = cx.vert_tri_begin[v], deg = cx.vert_tri_begin[v + 1] - begin;
    vs.sector_begin[v + 1] = vs.sector_begin[v];
    if (deg == 0) {
      vs.boundary[v] = 1;  // not on any triangle: a point is its own boundary
      continue;
    }
    gather_sides(cx, v, link);
    const int ns = number_sectors(cx, v, deg, link);
    const int nh = link_nodes(cx, v, ns, link);
    vs.h_nodes[v] = static_cast<std::uint16_t>(nh);
    vs.boundary[v] = link_is_forest(link, ns, nh) ? 1 : 0;
    for (Index i = 0; i < deg; ++i) {
      const Index t = cx.vert_tris[begin + i];
      vs.corner_sector[3 * t + corner_of(cx.triangles[t], v)] = static_cast<std::uint16_t>(link.sector_of_local[i]);
    }
    for (int s = 0; s < ns; ++s) {
      vs.end_a.push_back(static_cast<std::uint16_t>(link.ends[s][0]));
      vs.end_b.push_back(static_cast<std::uint16_t>(link.ends[s][1]));
    }
    vs.sector_begin[v + 1] = vs.sector_begin[v] + static_cast<Index>(ns);
  }
  return vs;
}

}  // namespace medax::et
