// Mesh checks on the raw polygon soup: combinatorics by sorting edges, fans and components by
// union-find, self-intersections with CGAL's box intersection and exact predicates (the same
// rules as CGAL::Polygon_mesh_processing::does_self_intersect, but on a soup, so broken input is
// safe).
#include <medax/services/mesh_check.hpp>

#include "cgal_mesh.hpp"
#include "plural.hpp"

#include <medax/union_find.hpp>

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace medax::services {

namespace {

using detail::Kernel;
using detail::Point;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

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

// ---- the parts of check_mesh -------------------------------------------------------------

void check_indices(const SurfaceMesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (Index v : mesh.faces[f])
      if (v >= nv)
        throw std::invalid_argument(
            fmt::format("face {} refers to vertex {} but the mesh has {} vertices", f, v, nv));
}

/// Duplicate vertices: equal coordinates, exactly.
std::size_t count_duplicate_vertices(const SurfaceMesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<Index> order(nv);
  std::iota(order.begin(), order.end(), Index{0});
  const auto less = [&](Index a, Index b) {
    const Vec3 &p = mesh.vertices[a], &q = mesh.vertices[b];
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::sort(order.begin(), order.end(), less);
  std::size_t duplicates = 0;
  for (std::size_t i = 1; i < nv; ++i)
    if (mesh.vertices[order[i]] == mesh.vertices[order[i - 1]]) ++duplicates;
  return duplicates;
}

/// Degenerate faces: a repeated corner (no valid edges: left out of the topology) or collinear
/// corners (exact predicate; kept in the topology, skipped by the intersection test).
struct FaceKinds {
  std::vector<char> repeated;  ///< a repeated corner
  std::vector<char> usable;    ///< neither repeated nor collinear corners
  std::size_t proper = 0;      ///< faces without a repeated corner
  std::size_t degenerate = 0;  ///< repeated or collinear corners
};

FaceKinds classify_faces(const SurfaceMesh& mesh) {
  const std::size_t nf = mesh.faces.size();
  FaceKinds kinds{std::vector<char>(nf, 0), std::vector<char>(nf, 0)};
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& [a, b, c] = mesh.faces[f];
    if (a == b || b == c || a == c) {
      kinds.repeated[f] = 1;
      ++kinds.degenerate;
      continue;
    }
    ++kinds.proper;
    if (CGAL::collinear(detail::to_point(mesh.vertices[a]), detail::to_point(mesh.vertices[b]),
                        detail::to_point(mesh.vertices[c])))
      ++kinds.degenerate;
    else
      kinds.usable[f] = 1;
  }
  return kinds;
}

/// Duplicate faces: the same vertex set as an earlier face (either orientation).
std::size_t count_duplicate_faces(const SurfaceMesh& mesh, const FaceKinds& kinds) {
  std::vector<Tri> sorted;
  sorted.reserve(kinds.proper);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (kinds.repeated[f]) continue;
    Tri t = mesh.faces[f];
    std::sort(t.begin(), t.end());
    sorted.push_back(t);
  }
  std::sort(sorted.begin(), sorted.end());
  std::size_t duplicates = 0;
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i] == sorted[i - 1]) ++duplicates;
  return duplicates;
}

/// Referenced vertices and connected components of the faces without a repeated corner (faces
/// sharing a vertex), numbered in the order of their lowest face.
struct FaceComponents {
  std::vector<char> referenced;  ///< per vertex: used by a face without a repeated corner
  std::vector<Index> of_face;    ///< per face (0 for faces with a repeated corner)
  std::size_t count = 0;
};

FaceComponents face_components(const SurfaceMesh& mesh, const FaceKinds& kinds) {
  const std::size_t nv = mesh.vertices.size(), nf = mesh.faces.size();
  FaceComponents c{std::vector<char>(nv, 0), std::vector<Index>(nf, 0)};
  UnionFind sets(nf);
  std::vector<std::int64_t> first_face(nv, -1);
  for (std::size_t f = 0; f < nf; ++f) {
    if (kinds.repeated[f]) continue;
    for (Index v : mesh.faces[f]) {
      c.referenced[v] = 1;
      if (first_face[v] < 0) first_face[v] = static_cast<std::int64_t>(f);
      else sets.unite(static_cast<Index>(f), static_cast<Index>(first_face[v]));
    }
  }
  // The representative is the lowest face of its set, so numbering the representatives in
  // increasing order numbers the components by their lowest face.
  std::vector<Index> number(nf, 0);
  for (std::size_t f = 0; f < nf; ++f)
    if (!kinds.repeated[f] && sets.find(static_cast<Index>(f)) == f) number[f] = static_cast<Index>(c.count++);
  for (std::size_t f = 0; f < nf; ++f)
    if (!kinds.repeated[f]) c.of_face[f] = number[sets.find(static_cast<Index>(f))];
  return c;
}

/// Vertices used by no face at all (those used only by faces with a repeated corner count as used).
std::size_t count_unreferenced(const SurfaceMesh& mesh, const FaceKinds& kinds, const std::vector<char>& referenced) {
  std::vector<char> used = referenced;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (kinds.repeated[f])
      for (Index v : mesh.faces[f]) used[v] = 1;
  return mesh.vertices.size() - static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
}

/// One face side, by its undirected edge.
struct Side {
  Index lo, hi;
  Index face;
  bool forward;  ///< the face runs lo -> hi
};

/// Every side of the faces without a repeated corner, sorted by undirected edge, then face.
std::vector<Side> sorted_sides(const SurfaceMesh& mesh, const FaceKinds& kinds) {
  std::vector<Side> sides;
  sides.reserve(3 * kinds.proper);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (kinds.repeated[f]) continue;
    const Tri& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<Index>(f), a < b});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  return sides;
}

/// Vertices whose corners form several classes (several fans). `corners` joins corner 3f + k
/// with the corners at the same vertex of the faces sharing an edge there.
std::size_t count_nonmanifold_vertices(const SurfaceMesh& mesh, const FaceKinds& kinds, UnionFind& corners) {
  std::vector<std::pair<Index, Index>> fans;  // (vertex, class)
  fans.reserve(3 * kinds.proper);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (!kinds.repeated[f])
      for (int k = 0; k < 3; ++k) fans.emplace_back(mesh.faces[f][k], corners.find(static_cast<Index>(3 * f + k)));
  std::sort(fans.begin(), fans.end());
  fans.erase(std::unique(fans.begin(), fans.end()), fans.end());
  std::size_t count = 0;
  for (std::size_t i = 1; i < fans.size(); ++i)
    if (fans[i].first == fans[i - 1].first && (i < 2 || fans[i - 2].first != fans[i].first)) ++count;
  return count;
}

/// Edges: boundary (one face), consistent or not (two), non-manifold (more); boundary loops
/// and non-manifold vertices. Returns the number of edges of each component.
std::vector<long long> check_edges(const SurfaceMesh& mesh, const FaceKinds& kinds, const FaceComponents& components,
                                   MeshReport& r) {
  const std::vector<Side> sides = sorted_sides(mesh, kinds);
  UnionFind corners(3 * mesh.faces.size());
  const auto corner = [&mesh](Index f, Index v) {
    const Tri& t = mesh.faces[f];
    return static_cast<Index>(3 * static_cast<std::size_t>(f) + (t[0] == v ? 0 : t[1] == v ? 1 : 2));
  };
  UnionFind boundary_sets(mesh.vertices.size());
  std::vector<char> on_boundary(mesh.vertices.size(), 0);
  std::vector<long long> component_edges(components.count, 0);
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) ++j;
    const std::size_t count = j - i;
    ++r.edges;
    ++component_edges[components.of_face[sides[i].face]];
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
  r.nonmanifold_vertices = count_nonmanifold_vertices(mesh, kinds, corners);
  std::vector<Index> loops;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (on_boundary[v]) loops.push_back(boundary_sets.find(static_cast<Index>(v)));
  std::sort(loops.begin(), loops.end());
  r.boundary_loops = static_cast<std::size_t>(std::unique(loops.begin(), loops.end()) - loops.begin());
  return component_edges;
}

/// Coordinates relative to the bounding box of the referenced vertices: (v − centre) / longest
/// side. Volumes and solid angles computed in it do not depend on the coordinates' scale (no
/// underflow or overflow of cubed lengths at 1e-120 or 1e120).
struct UnitFrame {
  Vec3 centre = Vec3::Zero();
  double size = 1;
  Vec3 operator()(const Vec3& v) const { return (v - centre) / size; }
};

UnitFrame unit_frame(const SurfaceMesh& mesh, const std::vector<char>& referenced) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (referenced[v]) lo = lo.cwiseMin(mesh.vertices[v]), hi = hi.cwiseMax(mesh.vertices[v]);
  UnitFrame frame;
  if (!(lo.array() <= hi.array()).all()) return frame;
  frame.centre = 0.5 * (lo + hi);
  const double size = (hi - lo).maxCoeff();
  if (size > 0 && std::isfinite(size)) frame.size = size;
  return frame;
}

/// Signed volume of each component in the unit frame.
std::vector<double> component_volumes(const SurfaceMesh& mesh, const FaceKinds& kinds,
                                      const FaceComponents& components, const UnitFrame& frame) {
  std::vector<double> six_volume(components.count, 0.0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (kinds.repeated[f]) continue;
    const auto& [a, b, c] = mesh.faces[f];
    six_volume[components.of_face[f]] +=
        frame(mesh.vertices[a]).dot(frame(mesh.vertices[b]).cross(frame(mesh.vertices[c])));
  }
  for (double& v : six_volume) v /= 6.0;
  return six_volume;
}

/// Solid angle of the triangle (a, b, c) seen from the origin (Van Oosterom and Strackee), signed
/// by the triangle's orientation.
double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  return 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
}

/// Components (closed, manifold, consistent) whose orientation does not fit their nesting: the
/// number of other shells containing a vertex of the shell (|winding number| > 1/2) is its depth;
/// even depths must have a positive volume, odd ones (cavities) a negative one.
std::size_t count_misoriented_shells(const SurfaceMesh& mesh, const FaceKinds& kinds,
                                     const FaceComponents& components, const UnitFrame& frame,
                                     const std::vector<double>& volumes) {
  const std::size_t n = components.count;
  std::vector<std::vector<Index>> faces_of(n);
  std::vector<Vec3> lo(n, Vec3::Constant(std::numeric_limits<double>::infinity())), hi(n, -lo[0]);
  std::vector<Vec3> probe(n);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (kinds.repeated[f]) continue;
    const Index c = components.of_face[f];
    if (faces_of[c].empty()) probe[c] = frame(mesh.vertices[mesh.faces[f][0]]);
    faces_of[c].push_back(static_cast<Index>(f));
    for (Index v : mesh.faces[f]) lo[c] = lo[c].cwiseMin(frame(mesh.vertices[v])), hi[c] = hi[c].cwiseMax(frame(mesh.vertices[v]));
  }
  const auto winding = [&](std::size_t d, const Vec3& p) {
    double total = 0;
    for (Index f : faces_of[d]) {
      const Tri& t = mesh.faces[f];
      total += solid_angle(frame(mesh.vertices[t[0]]) - p, frame(mesh.vertices[t[1]]) - p, frame(mesh.vertices[t[2]]) - p);
    }
    return total / (4.0 * 3.14159265358979323846);
  };
  std::size_t misoriented = 0;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t depth = 0;
    for (std::size_t d = 0; d < n; ++d) {
      const bool in_box = (probe[c].array() >= lo[d].array()).all() && (probe[c].array() <= hi[d].array()).all();
      if (d != c && in_box && std::abs(winding(d, probe[c])) > 0.5) ++depth;
    }
    if ((depth % 2 == 0) != (volumes[c] > 0)) ++misoriented;
  }
  return misoriented;
}

/// Genus per component of a closed manifold mesh, from its Euler characteristic.
void set_genus(const SurfaceMesh& mesh, const FaceKinds& kinds, const FaceComponents& components,
           const std::vector<long long>& component_edges, MeshReport& r) {
  std::vector<long long> chi(components.count, 0);
  std::vector<char> seen(mesh.vertices.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (kinds.repeated[f]) continue;
    chi[components.of_face[f]] += 1;
    for (Index v : mesh.faces[f])
      if (!seen[v]) seen[v] = 1, chi[components.of_face[f]] += 1;
  }
  long long total = 0;
  for (std::size_t c = 0; c < components.count; ++c) {
    const long long g = (2 - (chi[c] - component_edges[c])) / 2;
    r.genus_per_component.push_back(g);
    total += g;
  }
  r.genus = total;
}

}  // namespace

MeshReport check_mesh(const SurfaceMesh& mesh, const MeshCheckOptions& options) {
  const auto t0 = Clock::now();
  check_indices(mesh);
  MeshReport r;
  r.vertices = mesh.vertices.size();
  r.faces = mesh.faces.size();
  r.duplicate_vertices = count_duplicate_vertices(mesh);
  const FaceKinds kinds = classify_faces(mesh);
  r.degenerate_faces = kinds.degenerate;
  r.duplicate_faces = count_duplicate_faces(mesh, kinds);
  const FaceComponents components = face_components(mesh, kinds);
  r.components = components.count;
  r.unreferenced_vertices = count_unreferenced(mesh, kinds, components.referenced);
  const std::vector<long long> component_edges = check_edges(mesh, kinds, components, r);

  r.closed = kinds.proper > 0 && r.boundary_edges == 0;
  r.manifold = r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0;
  r.consistently_oriented = r.inconsistent_edges == 0;
  if (kinds.proper > 0) {
    const UnitFrame frame = unit_frame(mesh, components.referenced);
    const std::vector<double> volumes = component_volumes(mesh, kinds, components, frame);
    r.relative_volume = std::accumulate(volumes.begin(), volumes.end(), 0.0);
    r.signed_volume = r.relative_volume * frame.size * frame.size * frame.size;
    if (r.closed && r.manifold && r.consistently_oriented)
      r.misoriented_shells = count_misoriented_shells(mesh, kinds, components, frame, volumes);
  }
  r.outward = r.closed && r.manifold && r.consistently_oriented && r.relative_volume > 0;

  const auto referenced = static_cast<long long>(
      std::count(components.referenced.begin(), components.referenced.end(), 1));
  r.euler_characteristic = referenced - static_cast<long long>(r.edges) + static_cast<long long>(kinds.proper);
  if (r.closed && r.manifold) set_genus(mesh, kinds, components, component_edges, r);

  if (options.self_intersections) {
    const auto t1 = Clock::now();
    const SelfIntersections si = self_intersections(mesh, kinds.usable);
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
        fmt::format("{} (holes; {}): run `repair` with fill_holes: true, or close the holes in the mesh",
                    plural(boundary_loops, "boundary loop", "boundary loops"),
                    plural(boundary_edges, "boundary edge", "boundary edges")));
  if (nonmanifold_edges > 0)
    add(MeshProblemKind::NonManifoldEdges, false,
        plural(nonmanifold_edges, "non-manifold edge", "non-manifold edges") +
            " (3 or more faces on one edge, so the surface is not watertight): fix the mesh, or run `repair` with "
            "repair: true (splits them, then fills holes and removes self-intersections; refuses if the result is "
            "still invalid)");
  if (nonmanifold_vertices > 0)
    add(MeshProblemKind::NonManifoldVertices, false,
        plural(nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices") +
            " (the faces around it form several fans): fix the mesh, or run `repair` with repair: true "
            "(splits them, then removes the resulting self-intersections; refuses if the result is still "
            "invalid)");
  if (self_intersecting.value_or(false))
    add(MeshProblemKind::SelfIntersections, false,
        fmt::format("{} ({}): run `repair` with remove_self_intersections: true, or fix the mesh",
                    plural(intersecting_pairs, "self-intersecting triangle pair", "self-intersecting triangle pairs"),
                    plural(intersecting_faces, "face", "faces")));
  if (inconsistent_edges > 0)
    add(MeshProblemKind::InconsistentOrientation, true,
        plural(inconsistent_edges, "edge", "edges") +
            " where the two faces disagree in orientation: `repair` orients the faces consistently (automatic)");
  if (closed && manifold && consistently_oriented && !(relative_volume > 0))
    add(MeshProblemKind::InwardOrientation, true,
        fmt::format("faces oriented inward (signed volume {:.3g} <= 0, in units of the longest bounding-box side "
                    "cubed): `repair` flips them outward (automatic), or reorient the faces in the file",
                    relative_volume));
  else if (misoriented_shells > 0)
    add(MeshProblemKind::MisorientedShells, true,
        fmt::format("{} of {} face the wrong way for their nesting (a shell inside a solid faces outward: two "
                    "overlapping solids, or a cavity facing out): `repair` orients the shells to bound a volume, "
                    "making every nested shell a cavity (automatic); if a nested shell is a separate part, remove "
                    "it or move it out",
                    misoriented_shells, plural(components, "closed shell", "closed shells")));
  if (duplicate_vertices > 0)
    add(MeshProblemKind::DuplicateVertices, true,
        plural(duplicate_vertices, "duplicate vertex", "duplicate vertices") +
            " (same position as another vertex): `repair` merges them (automatic)");
  if (degenerate_faces > 0)
    add(MeshProblemKind::DegenerateFaces, true,
        plural(degenerate_faces, "degenerate face", "degenerate faces") +
            " (repeated or collinear corners, zero area): `repair` removes them (automatic)");
  if (duplicate_faces > 0)
    add(MeshProblemKind::DuplicateFaces, true,
        plural(duplicate_faces, "duplicate face", "duplicate faces") +
            " (same vertices as another face): `repair` removes them (automatic)");
  if (unreferenced_vertices > 0)
    add(MeshProblemKind::UnreferencedVertices, true,
        plural(unreferenced_vertices, "unreferenced vertex", "unreferenced vertices") +
            " (used by no face): `repair` drops them (automatic)");
  return out;
}

bool MeshReport::valid_solid() const {
  return faces > degenerate_faces && closed && manifold && consistently_oriented && outward &&
         misoriented_shells == 0 && !self_intersecting.value_or(false);
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
  std::string s = fmt::format("{} vertices, {} faces, {}, {}, {}", vertices, faces,
                              closed ? std::string("closed") : plural(boundary_loops, "hole", "holes"),
                              manifold ? "manifold" : "non-manifold", plural(components, "component", "components"));
  if (genus) s += fmt::format(", genus {}", *genus);
  s += fmt::format(", Euler characteristic {}", euler_characteristic);
  if (closed && manifold && consistently_oriented)
    s += !outward ? ", inward" : misoriented_shells > 0 ? ", " + plural(misoriented_shells, "misoriented shell", "misoriented shells") : ", outward";
  else if (!consistently_oriented) s += ", inconsistently oriented";
  if (!self_intersecting) s += ", self-intersections not tested";
  else if (*self_intersecting) s += ", " + plural(intersecting_pairs, "self-intersecting pair", "self-intersecting pairs");
  else s += ", no self-intersection";
  return s;
}

}  // namespace medax::services
