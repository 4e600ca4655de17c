#include "local_measures.hpp"

#include <medax/services/kdtree.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace medax::et {

namespace {

bool contains(const Ball& b, const Vec3& p) {
  return b.radius >= 0 && (p - b.centre).norm() <= b.radius * (1 + 1e-10) + 1e-14;
}

/// Ball through exactly the given points (1..4), or radius -1 when degenerate.
Ball circumball(const Vec3* p, int n) {
  Ball b;
  if (n == 1) return {p[0], 0.0};
  if (n == 2) return {0.5 * (p[0] + p[1]), 0.5 * (p[1] - p[0]).norm()};
  if (n == 3) {
    const Vec3 u = p[1] - p[0], v = p[2] - p[0], w = u.cross(v);
    const double w2 = w.squaredNorm();
    if (w2 <= 1e-24 * u.squaredNorm() * v.squaredNorm() || w2 == 0) return b;
    const Vec3 c = p[0] + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2 * w2);
    return {c, (c - p[0]).norm()};
  }
  Eigen::Matrix3d m;
  Vec3 rhs;
  for (int i = 0; i < 3; ++i) {
    const Vec3 d = p[i + 1] - p[0];
    m.row(i) = d.transpose();
    rhs[i] = 0.5 * d.squaredNorm();
  }
  const double det = m.determinant();
  const double scale = m.row(0).norm() * m.row(1).norm() * m.row(2).norm();
  if (!(std::abs(det) > 1e-12 * scale)) return b;
  const Vec3 x = m.fullPivLu().solve(rhs);
  return {p[0] + x, x.norm()};
}

/// Smallest ball enclosing the support points (at most 4) with all of them on or inside.
Ball support_ball(const Vec3* s, int n) {
  if (n == 0) return {};
  Ball best;
  for (int mask = 1; mask < (1 << n); ++mask) {
    Vec3 sub[4];
    int k = 0;
    for (int i = 0; i < n; ++i)
      if (mask & (1 << i)) sub[k++] = s[i];
    const Ball b = circumball(sub, k);
    if (b.radius < 0 || (best.radius >= 0 && b.radius >= best.radius)) continue;
    bool all = true;
    for (int i = 0; i < n && all; ++i) all = contains(b, s[i]);
    if (all) best = b;
  }
  return best;
}

Ball welzl(std::vector<Vec3>& p, std::size_t n, Vec3* support, int ns) {
  if (n == 0 || ns == 4) return support_ball(support, ns);
  const Vec3 q = p[n - 1];
  Ball b = welzl(p, n - 1, support, ns);
  if (contains(b, q)) return b;
  support[ns] = q;
  return welzl(p, n - 1, support, ns + 1);
}

}  // namespace

Ball min_enclosing_ball(std::vector<Vec3> points) {
  if (points.empty()) return {};
  Vec3 support[4];
  return welzl(points, points.size(), support, 0);
}

double max_pairwise_angle(const Vec3& centre, const std::vector<Vec3>& points) {
  double best = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      const Vec3 a = points[i] - centre, b = points[j] - centre;
      const double na = a.norm(), nb = b.norm();
      if (na == 0 || nb == 0) continue;
      best = std::max(best, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  return best;
}

std::vector<std::vector<Vec3>> medial_generators(const Shape& shape, const MedialComplex& medial,
                                                 double tolerance, std::string* source) {
  const std::size_t nv = medial.num_vertices();
  std::vector<std::vector<Vec3>> out(nv);
  const bool have = medial.generators.size() == nv && nv > 0 &&
                    (medial.generator_kind == "mesh_vertex" || medial.generator_kind == "sample");
  if (have) {
    const std::vector<Vec3>& pts =
        medial.generator_kind == "mesh_vertex" ? shape.mesh.vertices : shape.samples.points;
    for (std::size_t v = 0; v < nv; ++v)
      for (Index i : medial.generators[v]) {
        if (i >= pts.size())
          throw std::invalid_argument("medial vertex " + std::to_string(v) + " has generator " + std::to_string(i) +
                                      " but the shape has " + std::to_string(pts.size()) + " " +
                                      medial.generator_kind + "s");
        out[v].push_back(pts[i]);
      }
    if (source) *source = "generators (" + medial.generator_kind + ")";
    return out;
  }
  const std::vector<Vec3>& pts = !shape.mesh.vertices.empty() ? shape.mesh.vertices : shape.samples.points;
  if (pts.empty())
    throw std::invalid_argument(
        "the medial complex has no generators and the shape has neither mesh vertices nor samples to find them");
  const services::PointIndex index(pts);
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3& c = medial.centres[v];
    const double d0 = index.nearest(c).second;
    for (const auto& [i, d] : index.within(c, d0 * (1 + tolerance) + 1e-12)) out[v].push_back(pts[i]);
  }
  if (source) *source = !shape.mesh.vertices.empty() ? "nearest mesh vertices" : "nearest samples";
  return out;
}

}  // namespace medax::et
