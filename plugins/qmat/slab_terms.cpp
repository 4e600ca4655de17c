// The initial quadrics of Q-MAT (notes §1.2–1.3): slab planes per vertex, and the "add" terms of
// sheet-boundary and faceless edges, built once on the input complex.
#include "collapse.hpp"

#include <cmath>

namespace medax::qmat {

namespace {

Vec3 face_normal(const CollapseMesh& mesh, const Tri& t) {
  const Vec3 a = centre_of(mesh.spheres[t[0]]), b = centre_of(mesh.spheres[t[1]]), c = centre_of(mesh.spheres[t[2]]);
  return (b - a).cross(c - a).normalized();
}

/// One plane per endpoint along the sheet boundary, pointing away from the face (weight 0.1·β·γ²).
void add_boundary_terms(const CollapseMesh& mesh, Index i, Index j, Index face, const QmatOptions& o,
                        InitialQuadrics& q) {
  const Vec4 &mi = mesh.spheres[i], &mj = mesh.spheres[j];
  const Tri& t = mesh.face(face);
  const Index third = t[0] != i && t[0] != j ? t[0] : (t[1] != i && t[1] != j ? t[1] : t[2]);
  Vec3 n = face_normal(mesh, t).cross(centre_of(mi) - centre_of(mj));  // not normalised, as the code
  if (!n.allFinite()) return;
  if (n.dot(centre_of(mesh.spheres[third]) - centre_of(mi)) > 0) n = -n;
  const double gamma = stability_ratio(mi, mj);
  const double weight = 0.1 * o.boundary_weight * gamma * gamma;
  q.add[i] += SlabQuadric::tangent_plane(n, mi, weight);
  q.add[j] += SlabQuadric::tangent_plane(n, mj, weight);
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

void add_cone_terms(const CollapseMesh& mesh, Index i, Index j, const QmatOptions& o, InitialQuadrics& q) {
  const Vec4 &mi = mesh.spheres[i], &mj = mesh.spheres[j];
  const auto normals = o.cone_terms == ConeTerms::QmatCode ? code_cone_normals(mi, mj) : clean_cone_normals(mi, mj);
  for (const Vec3& n : normals) {
    q.add[i] += SlabQuadric::tangent_plane(n, mi);
    q.add[j] += SlabQuadric::tangent_plane(n, mj);
  }
  const double gamma = stability_ratio(mi, mj);
  for (const auto& [end, other] : {std::pair{i, j}, std::pair{j, i}})
    if (mesh.neighbours(end).size() == 1) {  // a curve tip: cap plane along the edge
      const Vec3 cap = centre_of(mesh.spheres[end]) - centre_of(mesh.spheres[other]);
      q.add[end] += SlabQuadric::tangent_plane(cap, mesh.spheres[end], 0.01 * gamma * gamma);
    }
}

void add_slab_terms(const CollapseMesh& mesh, InitialQuadrics& q) {
  for (Index f = 0; f < mesh.face_slots(); ++f) {
    const Tri& t = mesh.face(f);
    const auto normals = slab_normals(mesh.spheres[t[0]], mesh.spheres[t[1]], mesh.spheres[t[2]]);
    if (!normals) {
      ++q.invalid_faces;
      continue;
    }
    for (Index v : t)
      for (const Vec3& n : *normals) q.slab[v] += SlabQuadric::tangent_plane(n, mesh.spheres[v]);
  }
}

}  // namespace

InitialQuadrics initial_quadrics(const CollapseMesh& mesh, const QmatOptions& options) {
  InitialQuadrics q;
  q.slab.resize(mesh.size());
  q.add.resize(mesh.size());
  add_slab_terms(mesh, q);
  for (Index i = 0; i < mesh.size(); ++i)
    for (Index j : mesh.neighbours(i)) {
      if (j < i) continue;
      Index face = 0;
      const std::size_t faces = mesh.face_count(i, j, &face);
      if (faces == 1) add_boundary_terms(mesh, i, j, face, options, q);
      else if (faces == 0) add_cone_terms(mesh, i, j, options, q);
    }
  return q;
}

}  // namespace medax::qmat
