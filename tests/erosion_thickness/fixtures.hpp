#pragma once
// Synthetic medial complexes with known burn times (implementation notes §9) for the Erosion
// Thickness tests: triangulated rectangles ("pages") glued along shared seams.
#include <medax/medial_complex.hpp>

#include <cmath>
#include <functional>
#include <map>
#include <tuple>
#include <vector>

namespace medax::et::testing {

/// Adds a grid-triangulated planar quad origin + s*u_dir*len_u + t*v_dir*len_v (s, t in [0,1]),
/// nu x nv cells, reusing vertices at identical positions (so pages glue along seams).
class ComplexBuilder {
 public:
  Index vertex(const Vec3& p, double r) {
    const auto key = std::make_tuple(std::llround(p.x() * 1e9), std::llround(p.y() * 1e9), std::llround(p.z() * 1e9));
    auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    const Index i = mc.add_vertex(p, r);
    index_[key] = i;
    return i;
  }
  void page(const Vec3& origin, const Vec3& u, const Vec3& v, int nu, int nv,
            const std::function<double(const Vec3&)>& radius) {
    std::vector<Index> ids((nu + 1) * (nv + 1));
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {
        const Vec3 p = origin + u * (double(i) / nu) + v * (double(j) / nv);
        ids[j * (nu + 1) + i] = vertex(p, radius(p));
      }
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const Index a = ids[j * (nu + 1) + i], b = ids[j * (nu + 1) + i + 1];
        const Index c = ids[(j + 1) * (nu + 1) + i + 1], d = ids[(j + 1) * (nu + 1) + i];
        if ((i + j) % 2 == 0) {
          mc.add_face(a, b, c);
          mc.add_face(a, c, d);
        } else {
          mc.add_face(a, b, d);
          mc.add_face(b, c, d);
        }
      }
  }
  MedialComplex done() {
    mc.close_edges();
    return mc;
  }
  MedialComplex mc;

 private:
  std::map<std::tuple<long long, long long, long long>, Index> index_;
};

inline std::function<double(const Vec3&)> constant_radius(double r) {
  return [r](const Vec3&) { return r; };
}

/// W x H rectangle in the xy-plane, corner at the origin.
inline MedialComplex make_plate(double w, double h, int nu, int nv, const std::function<double(const Vec3&)>& radius) {
  ComplexBuilder b;
  b.page(Vec3::Zero(), Vec3(w, 0, 0), Vec3(0, h, 0), nu, nv, radius);
  return b.done();
}

/// Three pages on the seam {(u, 0, 0), u in [0, L]}: heights a, a, b in the directions at 90°,
/// 210° and 330° around the x-axis.
inline Vec3 book_direction(int page) {
  const double angle = M_PI / 2 + page * 2 * M_PI / 3;
  return Vec3(0, std::cos(angle), std::sin(angle));
}
inline MedialComplex make_book(double L, double a, double b, double r, int nu, int nv_per_unit) {
  ComplexBuilder builder;
  const double heights[3] = {a, a, b};
  for (int p = 0; p < 3; ++p)
    builder.page(Vec3::Zero(), Vec3(L, 0, 0), book_direction(p) * heights[p], nu,
                 std::max(1, int(std::lround(heights[p] * nv_per_unit))), constant_radius(r));
  return builder.done();
}

/// Annulus in the xy-plane (inner radius r0, outer r1), R constant: b1 = 1.
inline MedialComplex make_annulus(double r0, double r1, int nr, int nt, double radius) {
  MedialComplex mc;
  for (int j = 0; j <= nr; ++j)
    for (int i = 0; i < nt; ++i) {
      const double rr = r0 + (r1 - r0) * j / nr, a = 2 * M_PI * i / nt;
      mc.add_vertex(Vec3(rr * std::cos(a), rr * std::sin(a), 0), radius);
    }
  auto id = [&](int i, int j) { return Index(j * nt + (i % nt)); };
  for (int j = 0; j < nr; ++j)
    for (int i = 0; i < nt; ++i) {
      mc.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      mc.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  mc.close_edges();
  return mc;
}

/// Closed cube-sphere of radius rho centred at c (R constant), appended.
inline void add_sphere(MedialComplex& mc, const Vec3& c, double rho, int n, double radius) {
  // Cube-sphere: each face of a cube as an n x n grid, projected; shared vertices merged by key.
  const Vec3 axes[3] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  std::map<std::tuple<long long, long long, long long>, Index> ids;
  auto vid = [&](const Vec3& q) {
    const auto key = std::make_tuple(std::llround(q.x() * 1e9), std::llround(q.y() * 1e9), std::llround(q.z() * 1e9));
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    const Index i = mc.add_vertex(c + rho * q.normalized(), radius);
    ids[key] = i;
    return i;
  };
  for (int ax = 0; ax < 3; ++ax)
    for (int sign = -1; sign <= 1; sign += 2) {
      const Vec3 nrm = axes[ax] * sign, u = axes[(ax + 1) % 3], v = axes[(ax + 2) % 3] * sign;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          auto pt = [&](int ii, int jj) { return nrm + u * (2.0 * ii / n - 1) + v * (2.0 * jj / n - 1); };
          const Index a = vid(pt(i, j)), bb = vid(pt(i + 1, j)), cc = vid(pt(i + 1, j + 1)), d = vid(pt(i, j + 1));
          mc.add_face(a, bb, cc);
          mc.add_face(a, cc, d);
        }
    }
  mc.close_edges();
}

}  // namespace medax::et::testing
