#include "medial_mesh.hpp"

#include <medax/union_find.hpp>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/property_map/property_map.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace medax::msd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriIt = std::vector<K::Triangle_3>::const_iterator;
using SegIt = std::vector<K::Segment_3>::const_iterator;
using TriTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, TriIt>>>;
using SegTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_segment_primitive<K, SegIt>>>;
using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, double>;

K::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
Vec3 from_cgal(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

Segment sorted_edge(Index a, Index b) { return a < b ? Segment{a, b} : Segment{b, a}; }

/// Representative (lowest index) of each vertex after merging points closer than `tolerance`.
std::vector<Index> merged_vertices(const std::vector<Vec3>& points, double tolerance) {
  UnionFind sets(points.size());
  if (tolerance <= 0) {
    std::map<std::array<double, 3>, Index> seen;
    for (Index v = 0; v < points.size(); ++v) {
      auto [it, fresh] = seen.emplace(std::array<double, 3>{points[v].x(), points[v].y(), points[v].z()}, v);
      if (!fresh) sets.unite(it->second, v);
    }
  } else {
    // Grid of cell `tolerance`: a close pair lies in the same or a neighbouring cell.
    std::map<std::array<long long, 3>, std::vector<Index>> grid;
    auto cell = [&](const Vec3& p) {
      return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() / tolerance)),
                                      static_cast<long long>(std::floor(p.y() / tolerance)),
                                      static_cast<long long>(std::floor(p.z() / tolerance))};
    };
    for (Index v = 0; v < points.size(); ++v) {
      const auto c = cell(points[v]);
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz) {
            auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
            if (it == grid.end()) continue;
            for (Index u : it->second)
              if ((points[u] - points[v]).norm() < tolerance) sets.unite(u, v);
          }
      grid[c].push_back(v);
    }
  }
  std::vector<Index> rep(points.size());
  for (Index v = 0; v < points.size(); ++v) rep[v] = sets.find(v);
  return rep;
}

/// Vertices of the largest connected component (by vertex count, ties to the lowest vertex).
std::vector<char> largest_component(std::size_t n, const std::vector<Segment>& edges,
                                    const std::vector<Tri>& triangles) {
  UnionFind sets(n);
  for (const auto& e : edges) sets.unite(e[0], e[1]);
  for (const auto& t : triangles) sets.unite(t[0], t[1]), sets.unite(t[1], t[2]);
  std::vector<std::size_t> size(n, 0);
  std::vector<char> used(n, 0);
  for (const auto& e : edges) used[e[0]] = used[e[1]] = 1;
  for (const auto& t : triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  for (Index v = 0; v < n; ++v)
    if (used[v]) ++size[sets.find(v)];
  const auto best = static_cast<Index>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<char> keep(n, 0);
  for (Index v = 0; v < n; ++v) keep[v] = used[v] && sets.find(v) == best;
  return keep;
}

/// Dijkstra from `source`: distances and predecessors (a vertex is its own predecessor when
/// it is the source or unreachable).
void dijkstra(const Graph& graph, std::size_t source, std::vector<double>& dist, std::vector<std::size_t>& pred) {
  const auto n = boost::num_vertices(graph);
  dist.assign(n, 0);
  pred.assign(n, 0);
  const auto index = boost::get(boost::vertex_index, graph);
  boost::dijkstra_shortest_paths(graph, source,
                                 boost::predecessor_map(boost::make_iterator_property_map(pred.begin(), index))
                                     .distance_map(boost::make_iterator_property_map(dist.begin(), index))
                                     .weight_map(boost::get(boost::edge_bundle, graph)));
}

}  // namespace

struct MedialMesh::Tree {
  std::vector<K::Triangle_3> triangles;
  std::vector<K::Segment_3> segments;
  TriTree triangle_tree;
  SegTree segment_tree;
  Graph graph;
};

MedialMesh MedialMesh::from_complex(const MedialComplex& complex, double merge_tolerance) {
  const auto rep = merged_vertices(complex.centres, merge_tolerance);
  std::set<Tri> triangles;
  std::set<Segment> edges;
  for (const auto& f : complex.faces) {
    Tri t{rep[f[0]], rep[f[1]], rep[f[2]]};
    std::sort(t.begin(), t.end());
    if (t[0] == t[1] || t[1] == t[2]) {
      if (t[0] != t[2]) edges.insert(sorted_edge(t[0], t[2]));
      continue;
    }
    triangles.insert(t);
  }
  for (const auto& e : complex.edges)
    if (rep[e[0]] != rep[e[1]]) edges.insert(sorted_edge(rep[e[0]], rep[e[1]]));
  std::vector<Tri> tri_list(triangles.begin(), triangles.end());
  std::vector<Segment> edge_list(edges.begin(), edges.end());
  const auto keep = largest_component(complex.centres.size(), edge_list, tri_list);
  std::vector<Index> new_index(complex.centres.size(), 0);
  std::vector<Vec3> points;
  for (Index v = 0; v < complex.centres.size(); ++v)
    if (keep[v]) new_index[v] = static_cast<Index>(points.size()), points.push_back(complex.centres[v]);
  std::vector<Tri> kept_triangles;
  for (const auto& t : tri_list)
    if (keep[t[0]]) kept_triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  std::vector<Segment> kept_edges;
  for (const auto& e : edge_list)
    if (keep[e[0]]) kept_edges.push_back({new_index[e[0]], new_index[e[1]]});
  if (points.empty()) throw std::invalid_argument("the medial complex has no edge or triangle: M needs at least one");
  return MedialMesh(std::move(points), std::move(kept_triangles), std::move(kept_edges));
}

MedialMesh::MedialMesh(std::vector<Vec3> points, std::vector<Tri> triangles, std::vector<Segment> edges)
    : points_(std::move(points)), triangles_(std::move(triangles)), tree_(std::make_unique<Tree>()) {
  std::set<Segment> sides;
  for (const auto& t : triangles_)
    for (int i = 0; i < 3; ++i) sides.insert(sorted_edge(t[i], t[(i + 1) % 3]));
  std::set<Segment> dangling;
  for (const auto& e : edges)
    if (e[0] != e[1] && !sides.count(sorted_edge(e[0], e[1]))) dangling.insert(sorted_edge(e[0], e[1]));
  dangling_.assign(dangling.begin(), dangling.end());
  sides.insert(dangling.begin(), dangling.end());
  edges_.assign(sides.begin(), sides.end());
  build_incidence();
  build_distances();
}

MedialMesh::~MedialMesh() = default;
MedialMesh::MedialMesh(MedialMesh&&) noexcept = default;
MedialMesh& MedialMesh::operator=(MedialMesh&&) noexcept = default;

std::vector<Index> MedialMesh::facet_vertices(Index facet) const {
  if (is_triangle_facet(facet)) {
    const auto& t = triangles_[facet];
    return {t[0], t[1], t[2]};
  }
  const auto& e = dangling_[facet - triangles_.size()];
  return {e[0], e[1]};
}

std::optional<Index> MedialMesh::edge_index(Index a, Index b) const {
  const auto key = sorted_edge(a, b);
  auto it = std::lower_bound(edges_.begin(), edges_.end(), key);
  if (it == edges_.end() || *it != key) return std::nullopt;
  return static_cast<Index>(it - edges_.begin());
}

std::vector<Index> MedialMesh::facet_edges(Index facet) const {
  const auto v = facet_vertices(facet);
  if (v.size() == 2) return {*edge_index(v[0], v[1])};
  return {*edge_index(v[0], v[1]), *edge_index(v[1], v[2]), *edge_index(v[2], v[0])};
}

void MedialMesh::build_incidence() {
  edge_facets_.assign(edges_.size(), {});
  vertex_facets_.assign(points_.size(), {});
  for (Index f = 0; f < num_facets(); ++f) {
    for (Index v : facet_vertices(f)) vertex_facets_[v].push_back(f);
    for (Index e : facet_edges(f)) edge_facets_[e].push_back(f);
  }
  facet_neighbours_.assign(num_facets(), {});
  for (const auto& facets : edge_facets_)
    for (Index f : facets)
      for (Index g : facets)
        if (f != g) facet_neighbours_[f].push_back(g);
  for (auto& n : facet_neighbours_) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  adjacency_.assign(points_.size(), {});
  for (const auto& e : edges_) {
    const double length = (points_[e[0]] - points_[e[1]]).norm();
    adjacency_[e[0]].push_back({e[1], length});
    adjacency_[e[1]].push_back({e[0], length});
  }
  for (const auto& t : triangles_) tree_->triangles.emplace_back(to_cgal(points_[t[0]]), to_cgal(points_[t[1]]), to_cgal(points_[t[2]]));
  for (const auto& e : dangling_) tree_->segments.emplace_back(to_cgal(points_[e[0]]), to_cgal(points_[e[1]]));
  tree_->triangle_tree.rebuild(tree_->triangles.begin(), tree_->triangles.end());
  tree_->segment_tree.rebuild(tree_->segments.begin(), tree_->segments.end());
  if (!tree_->triangles.empty()) tree_->triangle_tree.accelerate_distance_queries();
  if (!tree_->segments.empty()) tree_->segment_tree.accelerate_distance_queries();
}

void MedialMesh::build_distances() {
  std::vector<std::pair<std::size_t, std::size_t>> arcs;
  std::vector<double> weights;
  for (Index v = 0; v < points_.size(); ++v)
    for (const auto& [u, w] : adjacency_[v]) arcs.emplace_back(v, u), weights.push_back(w);
  tree_->graph = Graph(boost::edges_are_unsorted_multi_pass, arcs.begin(), arcs.end(), weights.begin(), points_.size());
  const std::size_t n = points_.size();
  if (n > kAllPairsLimit) return;
  all_distances_.resize(n * n);
  all_predecessors_.resize(n * n);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t s) {
    std::vector<std::size_t> pred;
    std::vector<double> dist;
    dijkstra(tree_->graph, s, dist, pred);
    for (std::size_t v = 0; v < n; ++v) {
      all_distances_[s * n + v] = dist[v];
      all_predecessors_[s * n + v] = static_cast<Index>(pred[v]);
    }
  });
}

std::vector<double> MedialMesh::distances_from(Index source) const {
  const std::size_t n = points_.size();
  if (!all_distances_.empty()) return {all_distances_.begin() + source * n, all_distances_.begin() + (source + 1) * n};
  std::vector<double> dist;
  std::vector<std::size_t> pred;
  dijkstra(tree_->graph, source, dist, pred);
  return dist;
}

double MedialMesh::distance(Index a, Index b) const {
  if (!all_distances_.empty()) return all_distances_[std::size_t{a} * points_.size() + b];
  return distances_from(a)[b];
}

std::vector<Index> MedialMesh::shortest_path(Index a, Index b) const {
  const std::size_t n = points_.size();
  std::vector<Index> pred(n);
  if (!all_predecessors_.empty()) {
    std::copy(all_predecessors_.begin() + a * n, all_predecessors_.begin() + (a + 1) * n, pred.begin());
  } else {
    std::vector<std::size_t> p;
    std::vector<double> dist;
    dijkstra(tree_->graph, a, dist, p);
    std::copy(p.begin(), p.end(), pred.begin());
  }
  std::vector<Index> path{b};
  while (path.back() != a) {
    const Index previous = pred[path.back()];
    if (previous == path.back()) throw std::logic_error("shortest_path: the vertices are not connected on M");
    path.push_back(previous);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

MeshPoint MedialMesh::closest_point(const Vec3& p) const {
  MeshPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  const auto q = to_cgal(p);
  if (!tree_->triangles.empty()) {
    const auto [point, it] = tree_->triangle_tree.closest_point_and_primitive(q);
    best = {from_cgal(point), static_cast<Index>(it - tree_->triangles.begin()), std::sqrt(CGAL::squared_distance(q, point))};
  }
  if (!tree_->segments.empty()) {
    const auto [point, it] = tree_->segment_tree.closest_point_and_primitive(q);
    const double d = std::sqrt(CGAL::squared_distance(q, point));
    if (d < best.distance)
      best = {from_cgal(point), static_cast<Index>(triangles_.size() + (it - tree_->segments.begin())), d};
  }
  return best;
}

std::vector<Index> farthest_point_sites(const MedialMesh& mesh, std::size_t k, Index start) {
  const std::size_t n = mesh.points().size();
  if (start >= n) throw std::invalid_argument("farthest_point_sites: start vertex " + std::to_string(start) + " is not a vertex of M (it has " + std::to_string(n) + ")");
  std::vector<Index> sites;
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  Index next = start;
  while (sites.size() < std::min(k, n)) {
    sites.push_back(next);
    const auto d = mesh.distances_from(next);
    for (std::size_t v = 0; v < n; ++v) nearest[v] = std::min(nearest[v], d[v]);
    next = static_cast<Index>(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
  }
  return sites;
}

}  // namespace medax::msd
