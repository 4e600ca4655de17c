// The initial quadrics of Q-MAT (notes §1.2–1.3): slab planes per vertex, and the "add" terms of
// sheet-boundary and faceless edges, built once on the input complex. Each vertex's quadrics are
// summed on their own (in parallel) in the order of a sweep over the faces and then over the
// edges (lo, hi) in index order: its faces in index order, then its neighbours in index order.
#include "collapse.hpp"

#include <medax/services/blocks.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace medax::qmat {

namespace {

Vec3 face_normal(const CollapseMesh& mesh, const Tri& t) {
  const Vec3 a = centre_of(mesh.spheres[t[0]]), b = centre_of(mesh.spheres[t[1]]), c = centre_of(mesh.spheres[t[2]]);
  return (b - a).cross(c - a).normalized();
}

constexpr std::size_t kBlock = 2048;  // faces or vertices per parallel block

/// The plane at endpoint `end` of the sheet-boundary edge (i, j), i < j, pointing away from the
/// face (weight 0.1·β·γ²).
void add_boundary_term(const CollapseMesh& mesh, Index i, Index j, Index face, Index end, const QmatOptions& o,
                       SlabQuadric& add) {
  const Vec4 &mi = mesh.spheres[i], &mj = mesh.spheres[j];
  const Tri& t = mesh.face(face);
  const Index third = t[0] != i && t[0] != j ? t[0] : (t[1] != i && t[1] != j ? t[1] : t[2]);
  Vec3 n = face_normal(mesh, t).cross(centre_of(mi) - centre_of(mj));  // not normalised, as the code
  if (!n.allFinite()) return;
  if (n.dot(centre_of(mesh.spheres[third]) - centre_of(mi)) > 0) n = -n;
  const double gamma = stability_ratio(mi, mj);
  const double weight = 0.1 * o.boundary_weight * gamma * gamma;
  add += SlabQuadric::tangent_plane(n, mesh.spheres[end], weight);
}

/// The authors' pseudo-slab: third sphere at c₀ + c₁ (sic, not the midpoint, which would make
/// the slab degenerate), its two planes and their cross products with the edge.
std::vector<Vec3> code_cone_normals(const Vec4& mi, const Vec4& mj) {
  const Vec4 pseudo = sphere4(centre_of(mi) + centre_of(mj), 0.5 * (mi.w() + mj.w()));
  const auto normals = slab_normals(mi, mj, pseudo);
  if (!normals) return {};
  const Vec3 axis = centre_of(mi) - centre_of(mj);
  return {(*normals)[0], (*normals)[1], axis.cross((*normals)[0]), axis.cross((*normals)[1])};
}

/// The cone's tangent planes in four directions 90° apart around its axis; their sum does not
/// depend on the first direction chosen.
std::vector<Vec3> clean_cone_normals(const Vec4& mi, const Vec4& mj) {
  const Vec3 d = centre_of(mj) - centre_of(mi);
  const double length = d.norm();
  if (!(length > 0)) return {};
  const Vec3 u = d / length;
  const double s = (mi.w() - mj.w()) / length;  // n·u for a plane tangent to both spheres
  if (std::abs(s) > 1) return {};
  Eigen::Index axis;
  u.cwiseAbs().minCoeff(&axis);
  const Vec3 w1 = u.cross(Vec3::Unit(axis)).normalized(), w2 = u.cross(w1);
  const double t = std::sqrt(1 - s * s);
  return {s * u + t * w1, s * u - t * w1, s * u + t * w2, s * u - t * w2};
}

/// The terms of the faceless edge (i, j), i < j, at its endpoint `end`: the cone's planes, then
/// the cap plane along the edge when `end` is a curve tip.
void add_cone_terms(const CollapseMesh& mesh, Index i, Index j, Index end, const QmatOptions& o, SlabQuadric& add) {
  const Vec4 &mi = mesh.spheres[i], &mj = mesh.spheres[j];
  const auto normals = o.cone_terms == ConeTerms::QmatCode ? code_cone_normals(mi, mj) : clean_cone_normals(mi, mj);
  for (const Vec3& n : normals) add += SlabQuadric::tangent_plane(n, mesh.spheres[end]);
  if (mesh.neighbours(end).size() == 1) {  // a curve tip: cap plane along the edge
    const double gamma = stability_ratio(mi, mj);
    const Vec3 cap = centre_of(mesh.spheres[end]) - centre_of(mesh.spheres[end == i ? j : i]);
    add += SlabQuadric::tangent_plane(cap, mesh.spheres[end], 0.01 * gamma * gamma);
  }
}

using FaceNormals = std::vector<std::optional<std::array<Vec3, 2>>>;

/// The slab planes of v's faces (in face order), each anchored at v's sphere.
void add_slab_terms(const CollapseMesh& mesh, const FaceNormals& normals, Index v, SlabQuadric& slab) {
  for (Index f : mesh.face_list(v))
    if (normals[f])
      for (const Vec3& n : *normals[f]) slab += SlabQuadric::tangent_plane(n, mesh.spheres[v]);
}

/// The add terms at v of its sheet-boundary and faceless edges (in neighbour order).
void add_edge_terms(const CollapseMesh& mesh, const QmatOptions& o, Index v, SlabQuadric& add) {
  for (Index u : mesh.neighbours(v)) {
    const Index i = std::min(u, v), j = std::max(u, v);
    Index face = 0;
    const std::size_t faces = mesh.face_count(i, j, &face);
    if (faces == 1) add_boundary_term(mesh, i, j, face, v, o, add);
    else if (faces == 0) add_cone_terms(mesh, i, j, v, o, add);
  }
}

}  // namespace

InitialQuadrics initial_quadrics(const CollapseMesh& mesh, const QmatOptions& options) {
  InitialQuadrics q;
  FaceNormals normals(mesh.face_slots());
  services::for_blocks(normals.size(), kBlock, options.parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      const Tri& t = mesh.face(static_cast<Index>(f));
      normals[f] = slab_normals(mesh.spheres[t[0]], mesh.spheres[t[1]], mesh.spheres[t[2]]);
    }
  });
  q.invalid_faces = static_cast<std::size_t>(std::count(normals.begin(), normals.end(), std::nullopt));
  q.slab.resize(mesh.size());
  q.add_of.assign(mesh.size(), InitialQuadrics::kNoAdd);
  std::vector<std::vector<std::pair<Index, SlabQuadric>>> adds(services::block_count(mesh.size(), kBlock));
  services::for_blocks(mesh.size(), kBlock, options.parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    for (auto v = static_cast<Index>(begin); v < end; ++v) {
      SlabQuadric slab, add;
      add_slab_terms(mesh, normals, v, slab);
      q.slab[v] = PackedQuadric::pack(slab);
      add_edge_terms(mesh, options, v, add);
      if (!add.is_zero()) adds[b].emplace_back(v, add);
    }
  });
  for (const auto& block : adds)  // in vertex order
    for (const auto& [v, add] : block) {
      q.add_of[v] = static_cast<Index>(q.add.size());
      q.add.push_back(add);
    }
  return q;
}

}  // namespace medax::qmat
