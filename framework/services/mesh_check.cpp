// Mesh checks on the raw polygon soup: combinatorics by sorting edges, fans and components by
// union-find, self-intersections with CGAL's box intersection and exact predicates (the same
// rules as CGAL::Polygon_mesh_processing::does_self_intersect, but on a soup, so broken input is
// safe).
#include <medax/services/mesh_check.hpp>

#include "cgal_mesh.hpp"
#include "message_text.hpp"

#include <CGAL/box_intersection_d.h>
#include <Eigen/Geometry>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace medax::services {

namespace {

using detail::Kernel;
using detail::Point;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Union-find with path halving and union by size.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<std::size_t> parent_, size_;
};

using detail::cat;
using detail::plural;

/// Do two non-degenerate triangles of a soup intersect outside what they share? Shared corners
/// are recognised by index, as CGAL does for a mesh: distinct vertices at the same position do
/// not count as shared, so a surface touching itself there intersects.
bool triangles_intersect(const SurfaceMesh& mesh, const Tri& f, const Tri& g) {
  const auto P = [&mesh](Index v) { return detail::to_point(mesh.vertices[v]); };
  int shared = 0, fi = -1, gj = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (f[i] == g[j]) ++shared, fi = i, gj = j;
  if (shared == 3) return true;  // the same triangle twice: they overlap everywhere
  if (shared == 2) {
    // Shared edge (a, b): they overlap iff coplanar with the third corners on the same side.
    Index a = 0, b = 0, c = 0, d = 0;
    for (int i = 0; i < 3; ++i) {
      const bool in_g = f[i] == g[0] || f[i] == g[1] || f[i] == g[2];
      if (!in_g) c = f[i];
    }
    for (int j = 0; j < 3; ++j) {
      const bool in_f = g[j] == f[0] || g[j] == f[1] || g[j] == f[2];
      if (!in_f) d = g[j];
    }
    int k = 0;
    for (int i = 0; i < 3; ++i)
      if (f[i] != c) (k++ == 0 ? a : b) = f[i];
    return CGAL::coplanar(P(a), P(b), P(c), P(d)) &&
           CGAL::coplanar_orientation(P(a), P(b), P(c), P(d)) == CGAL::POSITIVE;
  }
  const Kernel::Triangle_3 tf(P(f[0]), P(f[1]), P(f[2]));
  const Kernel::Triangle_3 tg(P(g[0]), P(g[1]), P(g[2]));
  if (shared == 1) {
    // Shared corner: they intersect iff the edge opposite it in one meets the other triangle.
    const Kernel::Segment_3 sf(P(f[(fi + 1) % 3]), P(f[(fi + 2) % 3]));
    const Kernel::Segment_3 sg(P(g[(gj + 1) % 3]), P(g[(gj + 2) % 3]));
    return CGAL::do_intersect(tf, sg) || CGAL::do_intersect(tg, sf);
  }
  return CGAL::do_intersect(tf, tg);
}

struct SelfIntersections {
  std::size_t pairs = 0, faces = 0;
};

SelfIntersections self_intersections(const SurfaceMesh& mesh, const std::vector<char>& usable) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  boxes.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!usable[f]) continue;
    const auto& [a, b, c] = mesh.faces[f];
    const CGAL::Bbox_3 box = detail::to_point(mesh.vertices[a]).bbox() + detail::to_point(mesh.vertices[b]).bbox() +
                             detail::to_point(mesh.vertices[c]).bbox();
    boxes.emplace_back(box, static_cast<Index>(f));
  }
  std::vector<std::pair<Index, Index>> candidates;
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(
      boxes.begin(), boxes.end(),
      [&candidates](const Box& a, const Box& b) { candidates.emplace_back(a.info(), b.info()); });
  std::vector<char> hit(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        hit[i] = triangles_intersect(mesh, mesh.faces[candidates[i].first],
                                                     mesh.faces[candidates[i].second]);
                    });
  SelfIntersections out;
  std::vector<char> face_hit(mesh.faces.size(), 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!hit[i]) continue;
    ++out.pairs;
    face_hit[candidates[i].first] = face_hit[candidates[i].second] = 1;
  }
  out.faces = static_cast<std::size_t>(std::count(face_hit.begin(), face_hit.end(), 1));
  return out;
}

}  // namespace

MeshReport check_mesh(const SurfaceMesh& mesh, const MeshCheckOptions& options) {
  const auto t0 = Clock::now();
  MeshReport r;
  const std::size_t nv = mesh.vertices.size(), nf = mesh.faces.size();
  r.vertices = nv;
  r.faces = nf;
  for (std::size_t f = 0; f < nf; ++f)
    for (Index v : mesh.faces[f])
      if (v >= nv)
        throw std::invalid_argument(cat("face ", f, " refers to vertex ", v, " but the mesh has ", nv, " vertices"));

  // Duplicate vertices: equal coordinates, exactly.
  {
    std::vector<Index> order(nv);
    std::iota(order.begin(), order.end(), Index{0});
    const auto less = [&](Index a, Index b) {
      const Vec3 &p = mesh.vertices[a], &q = mesh.vertices[b];
      return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < nv; ++i)
      if (mesh.vertices[order[i]] == mesh.vertices[order[i - 1]]) ++r.duplicate_vertices;
  }

  // Degenerate faces: a repeated corner (no valid edges: left out of the topology below) or
  // collinear corners (exact predicate; kept in the topology, skipped by the intersection test).
  std::vector<char> repeated(nf, 0), usable(nf, 0);
  std::size_t proper_faces = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& [a, b, c] = mesh.faces[f];
    if (a == b || b == c || a == c) {
      repeated[f] = 1;
      ++r.degenerate_faces;
      continue;
    }
    ++proper_faces;
    if (CGAL::collinear(detail::to_point(mesh.vertices[a]), detail::to_point(mesh.vertices[b]),
                        detail::to_point(mesh.vertices[c])))
      ++r.degenerate_faces;
    else
      usable[f] = 1;
  }

  // Duplicate faces: the same vertex set as an earlier face (either orientation).
  {
    std::vector<Tri> sorted;
    sorted.reserve(proper_faces);
    for (std::size_t f = 0; f < nf; ++f) {
      if (repeated[f]) continue;
      Tri t = mesh.faces[f];
      std::sort(t.begin(), t.end());
      sorted.push_back(t);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i)
      if (sorted[i] == sorted[i - 1]) ++r.duplicate_faces;
  }

  // Referenced vertices and connected components (faces sharing a vertex).
  std::vector<char> referenced(nv, 0);
  UnionFind face_sets(nf);
  {
    std::vector<std::int64_t> first_face(nv, -1);
    for (std::size_t f = 0; f < nf; ++f) {
      if (repeated[f]) continue;
      for (Index v : mesh.faces[f]) {
        referenced[v] = 1;
        if (first_face[v] < 0) first_face[v] = static_cast<std::int64_t>(f);
        else face_sets.unite(f, static_cast<std::size_t>(first_face[v]));
      }
    }
  }
  std::size_t referenced_count = static_cast<std::size_t>(std::count(referenced.begin(), referenced.end(), 1));
  {
    // Vertices used only by faces with a repeated corner still count as used.
    std::vector<char> used = referenced;
    for (std::size_t f = 0; f < nf; ++f)
      if (repeated[f])
        for (Index v : mesh.faces[f]) used[v] = 1;
    r.unreferenced_vertices = nv - static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
  }
  std::vector<std::size_t> component_of(nf, 0);
  std::vector<std::size_t> roots;
  for (std::size_t f = 0; f < nf; ++f)
    if (!repeated[f]) roots.push_back(face_sets.find(f));
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  r.components = roots.size();
  for (std::size_t f = 0; f < nf; ++f)
    if (!repeated[f])
      component_of[f] = static_cast<std::size_t>(std::lower_bound(roots.begin(), roots.end(), face_sets.find(f)) -
                                                  roots.begin());

  // Edges: one entry per face side, sorted by undirected edge.
  struct Side {
    Index lo, hi;
    Index face;
    bool forward;  ///< the face runs lo -> hi
  };
  std::vector<Side> sides;
  sides.reserve(3 * proper_faces);
  for (std::size_t f = 0; f < nf; ++f) {
    if (repeated[f]) continue;
    const Tri& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<Index>(f), a < b});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  // Corner (3f + k) union-find: corners at the same vertex join when their faces share an edge
  // at that vertex; a vertex whose corners form several classes has several fans.
  UnionFind corners(3 * nf);
  const auto corner = [&mesh](Index f, Index v) {
    const Tri& t = mesh.faces[f];
    return 3 * static_cast<std::size_t>(f) + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  UnionFind boundary_sets(nv);
  std::vector<char> on_boundary(nv, 0);
  std::vector<long long> component_edges(r.components, 0);
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) ++j;
    const std::size_t count = j - i;
    ++r.edges;
    ++component_edges[component_of[sides[i].face]];
    if (count == 1) {
      ++r.boundary_edges;
      boundary_sets.unite(sides[i].lo, sides[i].hi);
      on_boundary[sides[i].lo] = on_boundary[sides[i].hi] = 1;
    } else if (count == 2) {
      if (sides[i].forward == sides[i + 1].forward) ++r.inconsistent_edges;
    } else {
      ++r.nonmanifold_edges;
    }
    for (std::size_t k = i + 1; k < j; ++k) {
      corners.unite(corner(sides[i].face, sides[i].lo), corner(sides[k].face, sides[k].lo));
      corners.unite(corner(sides[i].face, sides[i].hi), corner(sides[k].face, sides[k].hi));
    }
    i = j;
  }
  {
    std::vector<std::pair<Index, std::size_t>> fans;
    fans.reserve(3 * proper_faces);
    for (std::size_t f = 0; f < nf; ++f)
      if (!repeated[f])
        for (int k = 0; k < 3; ++k) fans.emplace_back(mesh.faces[f][k], corners.find(3 * f + k));
    std::sort(fans.begin(), fans.end());
    fans.erase(std::unique(fans.begin(), fans.end()), fans.end());
    for (std::size_t i = 1; i < fans.size(); ++i)
      if (fans[i].first == fans[i - 1].first && (i < 2 || fans[i - 2].first != fans[i].first))
        ++r.nonmanifold_vertices;
  }
  {
    std::vector<std::size_t> loops;
    for (std::size_t v = 0; v < nv; ++v)
      if (on_boundary[v]) loops.push_back(boundary_sets.find(v));
    std::sort(loops.begin(), loops.end());
    r.boundary_loops = static_cast<std::size_t>(std::unique(loops.begin(), loops.end()) - loops.begin());
  }

  r.closed = proper_faces > 0 && r.boundary_edges == 0;
  r.manifold = r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0;
  r.consistently_oriented = r.inconsistent_edges == 0;

  // Signed volume about the bounding-box centre (smaller round-off than about the origin).
  if (proper_faces > 0) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t v = 0; v < nv; ++v)
      if (referenced[v]) lo = lo.cwiseMin(mesh.vertices[v]), hi = hi.cwiseMax(mesh.vertices[v]);
    const Vec3 centre = 0.5 * (lo + hi);
    double six_volume = 0;
    for (std::size_t f = 0; f < nf; ++f) {
      if (repeated[f]) continue;
      const auto& [a, b, c] = mesh.faces[f];
      six_volume += (mesh.vertices[a] - centre).dot((mesh.vertices[b] - centre).cross(mesh.vertices[c] - centre));
    }
    r.signed_volume = six_volume / 6.0;
  }
  r.outward = r.closed && r.manifold && r.consistently_oriented && r.signed_volume > 0;

  // Euler characteristic and genus.
  const long long faces_count = static_cast<long long>(proper_faces);
  r.euler_characteristic = static_cast<long long>(referenced_count) - static_cast<long long>(r.edges) + faces_count;
  if (r.closed && r.manifold) {
    std::vector<long long> chi(r.components, 0);
    std::vector<char> seen(nv, 0);
    for (std::size_t f = 0; f < nf; ++f) {
      if (repeated[f]) continue;
      chi[component_of[f]] += 1;
      for (Index v : mesh.faces[f])
        if (!seen[v]) seen[v] = 1, chi[component_of[f]] += 1;
    }
    long long total = 0;
    for (std::size_t c = 0; c < r.components; ++c) {
      const long long g = (2 - (chi[c] - component_edges[c])) / 2;
      r.genus_per_component.push_back(g);
      total += g;
    }
    r.genus = total;
  }

  if (options.self_intersections) {
    const auto t1 = Clock::now();
    const SelfIntersections si = self_intersections(mesh, usable);
    r.self_intersecting = si.pairs > 0;
    r.intersecting_pairs = si.pairs;
    r.intersecting_faces = si.faces;
    r.self_intersection_seconds = seconds_since(t1);
  }
  r.seconds = seconds_since(t0);
  return r;
}

std::vector<MeshProblem> MeshReport::problems() const {
  std::vector<MeshProblem> out;
  const auto add = [&out](MeshProblemKind kind, bool automatic, std::string message) {
    out.push_back({kind, automatic, std::move(message)});
  };
  if (faces == 0 || faces == degenerate_faces) {
    add(MeshProblemKind::Empty, false, "the mesh has no usable face: check the input file");
    return out;
  }
  if (boundary_edges > 0)
    add(MeshProblemKind::Holes, false,
        cat(plural(boundary_loops, "boundary loop", "boundary loops"), " (holes; ",
            plural(boundary_edges, "boundary edge", "boundary edges"),
            "): run `repair` with fill_holes: true, or close the holes in the mesh"));
  if (nonmanifold_edges > 0)
    add(MeshProblemKind::NonManifoldEdges, false,
        cat(plural(nonmanifold_edges, "non-manifold edge", "non-manifold edges"),
            " (3 or more faces on one edge, so the surface is not watertight): fix the mesh, or run `repair` with repair: true (splits them, "
            "then fills holes and removes self-intersections; refuses if the result is still invalid)"));
  if (nonmanifold_vertices > 0)
    add(MeshProblemKind::NonManifoldVertices, false,
        cat(plural(nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices"),
            " (the faces around it form several fans): fix the mesh, or run `repair` with repair: true "
            "(splits them, then removes the resulting self-intersections; refuses if the result is still "
            "invalid)"));
  if (self_intersecting.value_or(false))
    add(MeshProblemKind::SelfIntersections, false,
        cat(plural(intersecting_pairs, "self-intersecting triangle pair", "self-intersecting triangle pairs"), " (",
            plural(intersecting_faces, "face", "faces"),
            "): run `repair` with remove_self_intersections: true, or fix the mesh"));
  if (inconsistent_edges > 0)
    add(MeshProblemKind::InconsistentOrientation, true,
        cat(plural(inconsistent_edges, "edge", "edges"),
            " where the two faces disagree in orientation: `repair` orients the faces consistently (automatic)"));
  if (closed && manifold && consistently_oriented && !(signed_volume > 0))
    add(MeshProblemKind::InwardOrientation, true,
        cat("faces oriented inward (signed volume ", signed_volume,
            " <= 0): `repair` flips them outward (automatic)"));
  if (duplicate_vertices > 0)
    add(MeshProblemKind::DuplicateVertices, true,
        cat(plural(duplicate_vertices, "duplicate vertex", "duplicate vertices"),
            " (same position as another vertex): `repair` merges them (automatic)"));
  if (degenerate_faces > 0)
    add(MeshProblemKind::DegenerateFaces, true,
        cat(plural(degenerate_faces, "degenerate face", "degenerate faces"),
            " (repeated or collinear corners, zero area): `repair` removes them (automatic)"));
  if (duplicate_faces > 0)
    add(MeshProblemKind::DuplicateFaces, true,
        cat(plural(duplicate_faces, "duplicate face", "duplicate faces"),
            " (same vertices as another face): `repair` removes them (automatic)"));
  if (unreferenced_vertices > 0)
    add(MeshProblemKind::UnreferencedVertices, true,
        cat(plural(unreferenced_vertices, "unreferenced vertex", "unreferenced vertices"),
            " (used by no face): `repair` drops them (automatic)"));
  return out;
}

bool MeshReport::valid_solid() const {
  return faces > degenerate_faces && closed && manifold && consistently_oriented && outward &&
         !self_intersecting.value_or(false);
}

std::string MeshReport::describe_problems() const {
  std::string text;
  for (const MeshProblem& p : problems()) {
    if (!text.empty()) text += '\n';
    text += p.message;
  }
  return text;
}

std::string MeshReport::summary() const {
  std::string s = cat(vertices, " vertices, ", faces, " faces, ",
                      closed ? std::string("closed") : plural(boundary_loops, "hole", "holes"), ", ",
                      manifold ? "manifold" : "non-manifold", ", ", plural(components, "component", "components"));
  if (genus) s += cat(", genus ", *genus);
  s += cat(", Euler characteristic ", euler_characteristic);
  if (closed && manifold && consistently_oriented) s += outward ? ", outward" : ", inward";
  else if (!consistently_oriented) s += ", inconsistently oriented";
  if (!self_intersecting) s += ", self-intersections not tested";
  else if (*self_intersecting) s += ", " + plural(intersecting_pairs, "self-intersecting pair", "self-intersecting pairs");
  else s += ", no self-intersection";
  return s;
}

}  // namespace medax::services
