// MSD skeleton construction, steps a–b (paper §4.2; notes): the restricted Voronoi pieces of
// every facet of M, then one connected component per cell (orphans relabelled).
#include "construction_split.hpp"

#include <medax/union_find.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace medax::msd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Step a: restricted Voronoi pieces.

/// A corner of a piece being clipped.
struct Corner {
  Vec3 point;
  Key key;
  long support;  ///< the polygon edge leaving this corner: -1-s = triangle side s, m >= 0 = bisector with m
};

/// Signed side of x for the bisector of sites i and j: <= 0 where i is at least as near.
double bisector_side(const Vec3& x, const Vec3& si, const Vec3& sj) {
  return 2 * x.dot(sj - si) - (sj.squaredNorm() - si.squaredNorm());
}

Key crossing_key(const MedialMesh& mesh, Index facet, long support, Index i, Index j) {
  if (support < 0) {
    const auto v = mesh.facet_vertices(facet);
    const auto s = static_cast<std::size_t>(-1 - support);
    const Index e = *mesh.edge_index(v[s], v[(s + 1) % v.size()]);
    const auto p = sorted_pair(i, j);
    return {1, e, p[0], p[1], kNone};
  }
  const auto t = sorted_tri(i, j, static_cast<Index>(support));
  return {2, facet, t[0], t[1], t[2]};
}

/// A dangling edge's interval clipped by the half-space nearer to i than to j.
std::vector<Corner> clip_interval(const MedialMesh& mesh, Index facet, const std::vector<Corner>& ends,
                                  const std::vector<Vec3>& sites, Index i, Index j) {
  const double g0 = bisector_side(ends[0].point, sites[i], sites[j]), g1 = bisector_side(ends[1].point, sites[i], sites[j]);
  if (g0 > 0 && g1 > 0) return {};
  if (g0 <= 0 && g1 <= 0) return ends;
  const double t = g0 / (g0 - g1);
  Corner crossing{ends[0].point + t * (ends[1].point - ends[0].point), crossing_key(mesh, facet, -1, i, j), -1};
  return g0 <= 0 ? std::vector<Corner>{ends[0], crossing} : std::vector<Corner>{crossing, ends[1]};
}

/// Sutherland–Hodgman clip of site i's polygon by the half-space nearer to i than to j.
std::vector<Corner> clip(const MedialMesh& mesh, Index facet, const std::vector<Corner>& polygon,
                         const std::vector<Vec3>& sites, Index i, Index j) {
  std::vector<Corner> out;
  const std::size_t n = polygon.size();
  std::vector<double> g(n);
  for (std::size_t k = 0; k < n; ++k) g[k] = bisector_side(polygon[k].point, sites[i], sites[j]);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = (k + 1) % n;
    const bool strict_cross = (g[k] < 0 && g[next] > 0) || (g[k] > 0 && g[next] < 0);
    if (g[k] <= 0) {
      Corner c = polygon[k];
      if (g[next] > 0 && !strict_cross) c.support = static_cast<long>(j);
      out.push_back(c);
    }
    if (strict_cross) {
      const double t = g[k] / (g[k] - g[next]);
      const Vec3 x = polygon[k].point + t * (polygon[next].point - polygon[k].point);
      const long leaving = g[k] < 0 ? static_cast<long>(j) : polygon[k].support;
      out.push_back({x, crossing_key(mesh, facet, polygon[k].support, i, j), leaving});
    }
  }
  return out;
}

/// The sites that may own part of a facet: a site farther from the facet than some site's
/// farthest corner owns nothing there (and its bisectors are implied by that site's).
std::vector<Index> candidate_sites(const std::vector<Vec3>& corners, const std::vector<Vec3>& sites) {
  std::vector<double> nearest(sites.size());
  double bound = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < sites.size(); ++s) {
    double farthest = 0;
    for (const auto& c : corners) farthest = std::max(farthest, (c - sites[s]).norm());
    bound = std::min(bound, farthest);
    const auto p = to_cgal(sites[s]);
    nearest[s] = corners.size() == 3
                     ? std::sqrt(CGAL::squared_distance(p, K::Triangle_3(to_cgal(corners[0]), to_cgal(corners[1]), to_cgal(corners[2]))))
                     : std::sqrt(CGAL::squared_distance(p, K::Segment_3(to_cgal(corners[0]), to_cgal(corners[1]))));
  }
  std::vector<Index> out;
  for (Index s = 0; s < sites.size(); ++s)
    if (nearest[s] <= bound) out.push_back(s);
  return out;
}

RvdPiece measured_piece(Index facet, Index site, const std::vector<Corner>& polygon) {
  RvdPiece piece{facet, site, site, {}, 0, Vec3::Zero()};
  for (const auto& c : polygon) piece.polygon.push_back(c.point);
  if (polygon.size() == 2) {
    piece.measure = (polygon[1].point - polygon[0].point).norm();
    piece.centroid = 0.5 * (polygon[0].point + polygon[1].point);
    return piece;
  }
  Vec3 weighted = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    const Vec3 &a = polygon[0].point, &b = polygon[k].point, &c = polygon[k + 1].point;
    const double area = 0.5 * (b - a).cross(c - a).norm();
    piece.measure += area;
    weighted += area * (a + b + c) / 3;
  }
  piece.centroid = piece.measure > 0 ? Vec3(weighted / piece.measure) : piece.polygon[0];
  return piece;
}

std::vector<Piece> facet_pieces(const MedialMesh& mesh, Index facet, const std::vector<Vec3>& sites) {
  const auto vertices = mesh.facet_vertices(facet);
  std::vector<Corner> start;
  std::vector<Vec3> corners;
  for (std::size_t s = 0; s < vertices.size(); ++s) {
    corners.push_back(mesh.points()[vertices[s]]);
    start.push_back({corners.back(), {0, vertices[s], kNone, kNone, kNone}, -1 - static_cast<long>(s)});
  }
  if (vertices.size() == 2) start[1].support = -1;  // both ends bound the one side
  std::vector<Piece> out;
  const auto candidates = candidate_sites(corners, sites);
  for (Index i : candidates) {
    auto polygon = start;
    for (Index j : candidates)
      if (j != i && polygon.size() >= 2)
        polygon = vertices.size() == 2 ? clip_interval(mesh, facet, polygon, sites, i, j) : clip(mesh, facet, polygon, sites, i, j);
    if (polygon.size() < vertices.size()) continue;  // empty or degenerate: i owns no part of the facet
    Piece piece{measured_piece(facet, i, polygon), {}};
    if (piece.rvd.measure <= 0) continue;
    for (const auto& c : polygon) piece.keys.push_back(c.key);
    out.push_back(std::move(piece));
  }
  return out;
}

// Step b: one connected component per cell.

SplitMesh split_mesh(const MedialMesh& mesh, const std::vector<Vec3>& sites) {
  SplitMesh split;
  for (Index f = 0; f < mesh.num_facets(); ++f)
    for (auto& piece : facet_pieces(mesh, f, sites)) split.pieces.push_back(std::move(piece));
  for (Index p = 0; p < split.pieces.size(); ++p)
    for (std::size_t c = 0; c < split.pieces[p].keys.size(); ++c) {
      const auto& key = split.pieces[p].keys[c];
      auto& list = split.key_pieces[key];
      if (list.empty() || list.back() != p) list.push_back(p);
      split.key_point.emplace(key, split.pieces[p].rvd.polygon[c]);
    }
  return split;
}

/// Components of pieces with the same cell that touch at a split vertex.
UnionFind cell_components(const SplitMesh& split) {
  UnionFind sets(split.pieces.size());
  for (const auto& [key, list] : split.key_pieces)
    for (std::size_t a = 1; a < list.size(); ++a)
      for (std::size_t b = 0; b < a; ++b)
        if (split.pieces[list[a]].rvd.cell == split.pieces[list[b]].rvd.cell) sets.unite(list[a], list[b]);
  return sets;
}

/// The piece holding each site: on the site's host facet, labelled with the site.
std::vector<Index> site_pieces(const MedialMesh& mesh, const SplitMesh& split, const std::vector<Vec3>& sites) {
  std::vector<Index> out(sites.size(), kNone);
  for (Index s = 0; s < sites.size(); ++s) {
    const Index host = mesh.closest_point(sites[s]).facet;
    for (Index p = 0; p < split.pieces.size(); ++p)
      if (split.pieces[p].rvd.facet == host && split.pieces[p].rvd.site == s) out[s] = p;
    if (out[s] == kNone)
      throw std::invalid_argument("site " + std::to_string(s) + " owns no part of its facet of M: it coincides with another site; give distinct sites");
  }
  return out;
}

/// Relabels every orphan component to the neighbouring component whose site is nearest its
/// centre (area-weighted centroid). Returns the number of orphans relabelled.
std::size_t fix_orphans(SplitMesh& split, const std::vector<Vec3>& sites, const std::vector<Index>& roots) {
  std::size_t relabelled = 0;
  for (bool changed = true; changed;) {
    changed = false;
    auto sets = cell_components(split);
    std::set<Index> rooted;
    for (Index r : roots) rooted.insert(sets.find(r));
    std::map<Index, std::pair<Vec3, double>> centre;  // component -> (weighted sum, measure)
    for (Index p = 0; p < split.pieces.size(); ++p) {
      // try_emplace with zeros: an Eigen vector is not zeroed by a default construction.
      auto& c = centre.try_emplace(sets.find(p), Vec3::Zero(), 0.0).first->second;
      c.first += split.pieces[p].rvd.measure * split.pieces[p].rvd.centroid;
      c.second += split.pieces[p].rvd.measure;
    }
    std::map<Index, std::set<Index>> neighbour_cells;  // orphan component -> cells touching it
    for (const auto& [key, list] : split.key_pieces)
      for (Index a : list)
        for (Index b : list)
          if (!rooted.count(sets.find(a)) && sets.find(a) != sets.find(b)) neighbour_cells[sets.find(a)].insert(split.pieces[b].rvd.cell);
    for (const auto& [component, cells] : neighbour_cells) {
      const Vec3 c = centre[component].first / std::max(centre[component].second, 1e-300);
      Index best = *cells.begin();
      for (Index cell : cells)
        if ((sites[cell] - c).norm() < (sites[best] - c).norm()) best = cell;
      for (Index p = 0; p < split.pieces.size(); ++p)
        if (sets.find(p) == component) split.pieces[p].rvd.cell = best;
      ++relabelled;
      changed = true;
      break;  // components changed: recompute them
    }
  }
  return relabelled;
}

void check_sites(const std::vector<Vec3>& sites) {
  if (sites.empty()) throw std::invalid_argument("no site: the skeleton needs at least one site on M");
  for (std::size_t a = 0; a < sites.size(); ++a)
    for (std::size_t b = a + 1; b < sites.size(); ++b)
      if (sites[a] == sites[b])
        throw std::invalid_argument("sites " + std::to_string(a) + " and " + std::to_string(b) + " coincide; give distinct sites");
}

}  // namespace

SplitMesh labelled_split(const MedialMesh& mesh, const std::vector<Vec3>& sites, ConstructionStats& stats) {
  check_sites(sites);
  auto split = split_mesh(mesh, sites);
  stats.orphan_components = fix_orphans(split, sites, site_pieces(mesh, split, sites));
  return split;
}

std::vector<Index> cells_at(const SplitMesh& split, const std::vector<Index>& pieces) {
  std::set<Index> cells;
  for (Index p : pieces) cells.insert(split.pieces[p].rvd.cell);
  return {cells.begin(), cells.end()};
}

}  // namespace medax::msd
