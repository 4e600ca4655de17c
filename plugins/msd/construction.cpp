#include "construction.hpp"

#include "construction_rdt.hpp"
#include "construction_split.hpp"

#include <medax/union_find.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

namespace medax::msd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriIt = std::vector<K::Triangle_3>::const_iterator;
using TriTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, TriIt>>>;

K::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// ---------------------------------------------------------------------------------------------
// Steps d–g work on the growing skeleton.
struct Builder {
  const MedialMesh& mesh;
  const SurfaceCrossing& surface;
  const ConstructionOptions& options;
  std::vector<Vec3> points;
  std::vector<char> is_site;
  std::vector<Index> host;
  std::map<Segment, std::vector<Index>> polylines;  ///< each RDT edge (low, high) -> its vertices
  ConstructionStats& stats;

  Index add_vertex(const Vec3& p, Index facet) {
    points.push_back(p);
    is_site.push_back(0);
    host.push_back(facet);
    return static_cast<Index>(points.size() - 1);
  }
};

/// A polyline on M from u to v: u, the M shortest path between a corner of u's facet and a
/// corner of v's facet (the pair that makes the whole path shortest), v. Each part lies on M.
/// Returns the points and the facet holding each part.
std::pair<std::vector<Vec3>, std::vector<Index>> path_on_mesh(const Builder& b, Index u, Index v) {
  const auto& mesh = b.mesh;
  double best = std::numeric_limits<double>::infinity();
  Index from = 0, to = 0;
  for (Index a : mesh.facet_vertices(b.host[u]))
    for (Index c : mesh.facet_vertices(b.host[v])) {
      const double length = (b.points[u] - mesh.points()[a]).norm() + mesh.distance(a, c) + (mesh.points()[c] - b.points[v]).norm();
      if (length < best) best = length, from = a, to = c;
    }
  std::vector<Vec3> points{b.points[u]};
  std::vector<Index> facets{b.host[u]};
  const auto path = mesh.shortest_path(from, to);
  for (std::size_t k = 0; k < path.size(); ++k) {
    points.push_back(mesh.points()[path[k]]);
    facets.push_back(k + 1 < path.size() ? mesh.edge_facets(*mesh.edge_index(path[k], path[k + 1]))[0] : b.host[v]);
  }
  points.push_back(b.points[v]);
  return {points, facets};
}

/// The point of the polyline nearest to x, with the facet of its part and its arc length
/// from the start.
std::pair<MeshPoint, double> project_on_polyline(const std::vector<Vec3>& points, const std::vector<Index>& facets,
                                                 const Vec3& x) {
  MeshPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  double arc = 0, best_arc = 0;
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const Vec3 d = points[k + 1] - points[k];
    const double t = d.squaredNorm() > 0 ? std::clamp((x - points[k]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const Vec3 p = points[k] + t * d;
    if ((p - x).norm() < best.distance) best = {p, facets[k], (p - x).norm()}, best_arc = arc + t * d.norm();
    arc += d.norm();
  }
  return {best, best_arc};
}

/// The point at arc length `target` along the polyline, with the facet of its part.
MeshPoint point_at_arc(const std::vector<Vec3>& points, const std::vector<Index>& facets, double target) {
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const double length = (points[k + 1] - points[k]).norm();
    if (target <= length && length > 0) return {points[k] + (target / length) * (points[k + 1] - points[k]), facets[k], 0};
    target -= length;
  }
  return {points.back(), facets.back(), 0};
}

/// Where step e splits an edge: its midpoint projected onto the M path between its ends, or,
/// when that lands in the first or last quarter of the path (a path that winds away from the
/// straight edge, where the projection would not shorten the parts), the path's middle.
MeshPoint split_point(const std::vector<Vec3>& path, const std::vector<Index>& facets, const Vec3& midpoint) {
  double total = 0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) total += (path[k + 1] - path[k]).norm();
  const auto [projected, arc] = project_on_polyline(path, facets, midpoint);
  if (arc >= 0.25 * total && arc <= 0.75 * total) return projected;
  return point_at_arc(path, facets, 0.5 * total);
}

/// Step e for one edge: the vertices of its revision, u first, v last.
std::vector<Index> bisect_until_inside(Builder& b, Index u, Index v, int depth) {
  if (!b.surface.crosses(b.points[u], b.points[v])) return {u, v};
  const auto [path, facets] = path_on_mesh(b, u, v);
  const double too_close = 1e-9 * (b.points[u] - b.points[v]).norm();
  auto at_an_end = [&](const MeshPoint& m) {
    return (m.point - b.points[u]).norm() <= too_close || (m.point - b.points[v]).norm() <= too_close;
  };
  const auto m = split_point(path, facets, 0.5 * (b.points[u] + b.points[v]));
  if (depth >= b.options.max_bisection_depth || at_an_end(m)) {
    ++b.stats.unresolved_edges;
    return {u, v};
  }
  const Index mid = b.add_vertex(m.point, m.facet);
  ++b.stats.bisections;
  auto left = bisect_until_inside(b, u, mid, depth + 1);
  const auto right = bisect_until_inside(b, mid, v, depth + 1);
  left.insert(left.end(), right.begin() + 1, right.end());
  return left;
}

/// Step d: the groups of split vertices shared by cells a and b, joined along piece boundaries.
std::vector<std::vector<Key>> interfaces(const SplitMesh& split, Index a, Index b) {
  std::map<Key, Index> id;
  for (const auto& [key, list] : split.key_pieces) {
    const auto cells = cells_at(split, list);
    if (std::binary_search(cells.begin(), cells.end(), a) && std::binary_search(cells.begin(), cells.end(), b))
      id.emplace(key, static_cast<Index>(id.size()));
  }
  UnionFind sets(id.size());
  for (const auto& piece : split.pieces) {
    if (piece.rvd.cell != a) continue;
    for (std::size_t c = 0; c < piece.keys.size(); ++c) {
      auto p = id.find(piece.keys[c]), q = id.find(piece.keys[(c + 1) % piece.keys.size()]);
      if (p != id.end() && q != id.end()) sets.unite(p->second, q->second);
    }
  }
  std::map<Index, std::vector<Key>> groups;
  for (const auto& [key, index] : id) groups[sets.find(index)].push_back(key);
  std::vector<std::vector<Key>> out;
  for (auto& g : groups) out.push_back(std::move(g.second));
  return out;
}

Vec3 mean_point(const SplitMesh& split, const std::vector<Key>& keys) {
  Vec3 mean = Vec3::Zero();
  for (const auto& key : keys) mean += split.key_point.at(key);
  return mean / static_cast<double>(keys.size());
}

/// The facet of a piece touching a split vertex (the first one).
Index key_facet(const SplitMesh& split, const Key& key) { return split.pieces[split.key_pieces.at(key)[0]].rvd.facet; }

/// Step d: for every interface of a pair beyond the one the straight edge stands for (the one
/// nearest the sites' midpoint), a vertex at the interface's split point nearest its mean.
std::vector<std::array<Index, 3>> extra_interface_paths(Builder& b, const SplitMesh& split, const Rdt& rdt) {
  std::vector<std::array<Index, 3>> paths;
  for (const auto& e : rdt.edges) {
    const auto groups = interfaces(split, e[0], e[1]);
    if (groups.size() < 2) continue;
    const Vec3 middle = 0.5 * (b.points[e[0]] + b.points[e[1]]);
    std::size_t primary = 0;
    for (std::size_t g = 1; g < groups.size(); ++g)
      if ((mean_point(split, groups[g]) - middle).norm() < (mean_point(split, groups[primary]) - middle).norm()) primary = g;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (g == primary) continue;
      const Vec3 mean = mean_point(split, groups[g]);
      const Key* nearest = &groups[g][0];
      for (const auto& key : groups[g])
        if ((split.key_point.at(key) - mean).norm() < (split.key_point.at(*nearest) - mean).norm()) nearest = &key;
      const Index mid = b.add_vertex(split.key_point.at(*nearest), key_facet(split, *nearest));
      paths.push_back({e[0], mid, e[1]});
    }
  }
  b.stats.extra_interfaces = paths.size();
  return paths;
}

/// Step f: a triangle whose sides were revised, as the 3D polygon of its revised sides,
/// triangulated by CGAL's minimum-area hole filling (Liepa).
std::vector<Tri> retriangulate(const Builder& b, const Tri& t) {
  std::vector<Index> ring;
  for (int s = 0; s < 3; ++s) {
    const Index u = t[s], v = t[(s + 1) % 3];
    auto side = b.polylines.at(sorted_pair(u, v));
    if (side.front() != u) std::reverse(side.begin(), side.end());
    ring.insert(ring.end(), side.begin(), side.end() - 1);
  }
  if (ring.size() == 3) return {t};
  std::vector<K::Point_3> polyline;
  for (Index v : ring) polyline.push_back(to_cgal(b.points[v]));
  std::vector<CGAL::Triple<int, int, int>> patch;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(polyline, std::back_inserter(patch));
  if (patch.empty())  // hole filling found no triangulation: fan from the first corner
    for (int k = 1; k + 1 < static_cast<int>(ring.size()); ++k) patch.emplace_back(0, k, k + 1);
  std::vector<Tri> out;
  for (const auto& p : patch) out.push_back(sorted_tri(ring[p.first], ring[p.second], ring[p.third]));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Step g.
struct Elements {
  std::set<Segment> edges;
  std::set<Tri> triangles;
};

/// Removes degree-2 non-site vertices on straight chains (angle above the option) when the
/// replacing segment does not cross S.
void collapse_straight_vertices(Builder& b, Elements& el) {
  const double limit = b.options.collapse_angle_deg * M_PI / 180;
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::vector<Index>> neighbours(b.points.size());
    std::vector<char> in_triangle(b.points.size(), 0);
    for (const auto& e : el.edges) neighbours[e[0]].push_back(e[1]), neighbours[e[1]].push_back(e[0]);
    for (const auto& t : el.triangles) in_triangle[t[0]] = in_triangle[t[1]] = in_triangle[t[2]] = 1;
    for (Index v = 0; v < b.points.size() && !changed; ++v) {
      if (b.is_site[v] || in_triangle[v] || neighbours[v].size() != 2) continue;
      const Index a = neighbours[v][0], c = neighbours[v][1];
      const Vec3 da = b.points[a] - b.points[v], dc = b.points[c] - b.points[v];
      const double angle = std::acos(std::clamp(da.normalized().dot(dc.normalized()), -1.0, 1.0));
      if (angle <= limit || el.edges.count(sorted_pair(a, c)) || b.surface.crosses(b.points[a], b.points[c])) continue;
      el.edges.erase(sorted_pair(a, v));
      el.edges.erase(sorted_pair(v, c));
      el.edges.insert(sorted_pair(a, c));
      ++b.stats.collapsed;
      changed = true;
    }
  }
}

/// Drops triangle sides from the edges, unused non-site vertices, and renumbers.
Skeleton assemble(const Builder& b, const Elements& el) {
  std::set<Segment> sides;
  for (const auto& t : el.triangles) sides.insert({t[0], t[1]}), sides.insert({t[1], t[2]}), sides.insert({t[0], t[2]});
  std::vector<char> used(b.points.size(), 0);
  for (Index v = 0; v < b.points.size(); ++v) used[v] = b.is_site[v];
  for (const auto& e : el.edges) used[e[0]] = used[e[1]] = 1;
  for (const auto& t : el.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  Skeleton s;
  std::vector<Index> index(b.points.size(), kNone);
  for (Index v = 0; v < b.points.size(); ++v)
    if (used[v]) {
      index[v] = static_cast<Index>(s.vertices.size());
      s.vertices.push_back(b.points[v]);
      s.is_site.push_back(b.is_site[v]);
      s.host_facet.push_back(b.host[v]);
    }
  for (const auto& e : el.edges)
    if (!sides.count(e)) s.edges.push_back(sorted_pair(index[e[0]], index[e[1]]));
  for (const auto& t : el.triangles) s.triangles.push_back(sorted_tri(index[t[0]], index[t[1]], index[t[2]]));
  std::sort(s.edges.begin(), s.edges.end());
  std::sort(s.triangles.begin(), s.triangles.end());
  return s;
}

std::vector<MeshPoint> projected_sites(const MedialMesh& mesh, const std::vector<Vec3>& sites) {
  std::vector<MeshPoint> out;
  for (const auto& s : sites) out.push_back(mesh.closest_point(s));
  return out;
}

/// Steps d–f: every RDT edge (and every extra-interface path) revised, triangles rebuilt.
Elements revised_elements(Builder& b, const SplitMesh& split, const Rdt& rdt) {
  std::vector<std::vector<Index>> chains;
  for (const auto& e : rdt.edges) chains.push_back({e[0], e[1]});
  if (b.options.multi_interface)
    for (const auto& p : extra_interface_paths(b, split, rdt)) chains.push_back({p[0], p[1]}), chains.push_back({p[1], p[2]});
  Elements el;
  for (const auto& chain : chains) {
    const auto revised = bisect_until_inside(b, chain[0], chain[1], 0);
    for (std::size_t k = 0; k + 1 < revised.size(); ++k) el.edges.insert(sorted_pair(revised[k], revised[k + 1]));
    if (rdt.edges.count(sorted_pair(chain[0], chain[1]))) b.polylines[sorted_pair(chain[0], chain[1])] = revised;
  }
  for (const auto& t : rdt.triangles) {
    const auto parts = retriangulate(b, t);
    b.stats.retriangulated += parts.size() > 1;
    for (const auto& p : parts)
      if (p[0] != p[1] && p[1] != p[2]) el.triangles.insert(p);
  }
  return el;
}

}  // namespace

struct SurfaceCrossing::Impl {
  std::vector<K::Triangle_3> triangles;
  TriTree tree;
};

SurfaceCrossing::SurfaceCrossing(const SurfaceMesh& surface) : impl_(std::make_unique<Impl>()) {
  for (const auto& f : surface.faces)
    impl_->triangles.emplace_back(to_cgal(surface.vertices[f[0]]), to_cgal(surface.vertices[f[1]]), to_cgal(surface.vertices[f[2]]));
  impl_->tree.rebuild(impl_->triangles.begin(), impl_->triangles.end());
}
SurfaceCrossing::~SurfaceCrossing() = default;
SurfaceCrossing::SurfaceCrossing(SurfaceCrossing&&) noexcept = default;
SurfaceCrossing& SurfaceCrossing::operator=(SurfaceCrossing&&) noexcept = default;

bool SurfaceCrossing::crosses(const Vec3& a, const Vec3& b) const {
  return impl_->tree.do_intersect(K::Segment_3(to_cgal(a), to_cgal(b)));
}

bool SurfaceCrossing::crosses(const Vec3& a, const Vec3& b, const Vec3& c) const {
  return impl_->tree.do_intersect(K::Triangle_3(to_cgal(a), to_cgal(b), to_cgal(c)));
}

std::vector<RvdPiece> restricted_voronoi(const MedialMesh& mesh, const std::vector<Vec3>& sites) {
  std::vector<Vec3> on_mesh;
  for (const auto& p : projected_sites(mesh, sites)) on_mesh.push_back(p.point);
  ConstructionStats stats;
  auto split = labelled_split(mesh, on_mesh, stats);
  std::vector<RvdPiece> out;
  for (auto& piece : split.pieces) out.push_back(std::move(piece.rvd));
  return out;
}

std::vector<Vec3> cell_centroids(const std::vector<RvdPiece>& pieces, std::size_t num_sites) {
  std::vector<Vec3> weighted(num_sites, Vec3::Zero());
  std::vector<double> measure(num_sites, 0);
  std::vector<char> has_area(num_sites, 0);
  for (const auto& p : pieces) has_area[p.cell] |= p.polygon.size() >= 3;
  for (const auto& p : pieces)
    if (has_area[p.cell] == (p.polygon.size() >= 3)) weighted[p.cell] += p.measure * p.centroid, measure[p.cell] += p.measure;
  std::vector<Vec3> out(num_sites);
  for (std::size_t c = 0; c < num_sites; ++c)
    out[c] = measure[c] > 0 ? Vec3(weighted[c] / measure[c]) : Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  return out;
}

Skeleton construct_skeleton(const MedialMesh& mesh, const std::vector<Vec3>& sites, const SurfaceCrossing& surface,
                            const ConstructionOptions& options) {
  ConstructionStats stats;
  const auto projected = projected_sites(mesh, sites);
  Builder b{mesh, surface, options, {}, {}, {}, {}, stats};
  for (const auto& p : projected) b.points.push_back(p.point), b.is_site.push_back(1), b.host.push_back(p.facet);
  const auto split = labelled_split(mesh, b.points, stats);
  auto rdt = dual_complex(split, b.points, stats);
  stats.tetrahedra_thinned = thin_tetrahedra(rdt, b.points);
  auto el = revised_elements(b, split, rdt);
  collapse_straight_vertices(b, el);
  Skeleton skeleton = assemble(b, el);
  for (const auto& t : skeleton.triangles)
    stats.crossing_triangles += surface.crosses(skeleton.vertices[t[0]], skeleton.vertices[t[1]], skeleton.vertices[t[2]]);
  for (const auto& piece : split.pieces) skeleton.pieces.push_back(piece.rvd);
  skeleton.stats = stats;
  return skeleton;
}

}  // namespace medax::msd
