#include <medax/testing/shapes.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace medax::testing {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Midpoint subdivision of a unit icosahedron, vertices pushed to the unit sphere.
SurfaceMesh unit_icosphere(int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  SurfaceMesh m;
  for (const auto& v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t),
                        Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1),
                        Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.vertices.push_back(v.normalized());
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<Index, Index>, Index> midpoints;
    const auto midpoint = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0);
      if (inserted) {
        m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
        it->second = static_cast<Index>(m.vertices.size() - 1);
      }
      return it->second;
    };
    std::vector<Tri> faces;
    faces.reserve(m.faces.size() * 4);
    for (const Tri& f : m.faces) {
      const Index ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({f[1], bc, ab});
      faces.push_back({f[2], ca, bc});
      faces.push_back({ab, bc, ca});
    }
    m.faces = std::move(faces);
  }
  return m;
}

/// A closed surface of revolution about z from a profile (rho_i, z_i), i = 0..n-1, whose first
/// and last points lie on the axis (rho = 0). Rings with `segments` vertices; poles are single
/// vertices. The profile runs from bottom to top.
SurfaceMesh revolve(const std::vector<std::pair<double, double>>& profile, int segments) {
  SurfaceMesh m;
  const std::size_t rings = profile.size() - 2;
  m.vertices.emplace_back(0, 0, profile.front().second);
  for (std::size_t i = 1; i + 1 < profile.size(); ++i)
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * kPi * s / segments;
      m.vertices.emplace_back(profile[i].first * std::cos(phi), profile[i].first * std::sin(phi), profile[i].second);
    }
  m.vertices.emplace_back(0, 0, profile.back().second);
  const Index top = static_cast<Index>(m.vertices.size() - 1);
  const auto ring = [&](std::size_t r, int s) { return static_cast<Index>(1 + r * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) m.faces.push_back({0, ring(0, s + 1), ring(0, s)});
  for (std::size_t r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.faces.push_back({ring(r, s), ring(r, s + 1), ring(r + 1, s + 1)});
      m.faces.push_back({ring(r, s), ring(r + 1, s + 1), ring(r + 1, s)});
    }
  for (int s = 0; s < segments; ++s) m.faces.push_back({top, ring(rings - 1, s), ring(rings - 1, s + 1)});
  return m;
}

}  // namespace

SurfaceMesh make_sphere(double r, int subdivisions) {
  SurfaceMesh m = unit_icosphere(subdivisions);
  for (Vec3& v : m.vertices) v *= r;
  return m;
}

SurfaceMesh make_ellipsoid(double a, double b, double c, int subdivisions) {
  SurfaceMesh m = unit_icosphere(subdivisions);
  for (Vec3& v : m.vertices) v = Vec3(a * v.x(), b * v.y(), c * v.z());
  return m;
}

SurfaceMesh make_capsule(double radius, double half_length, int segments) {
  std::vector<std::pair<double, double>> profile;
  const int cap_steps = std::max(2, segments / 4);
  for (int i = 0; i <= cap_steps; ++i) {  // bottom hemisphere, from the pole up to the equator
    const double a = -kPi / 2 + (kPi / 2) * i / cap_steps;
    profile.emplace_back(radius * std::cos(a), -half_length + radius * std::sin(a));
  }
  const double spacing = 2 * kPi * radius / segments;
  const int body_steps = std::max(1, static_cast<int>(std::ceil(2 * half_length / spacing)));
  for (int i = 1; i < body_steps; ++i) profile.emplace_back(radius, -half_length + 2 * half_length * i / body_steps);
  for (int i = 0; i <= cap_steps; ++i) {
    const double a = (kPi / 2) * i / cap_steps;
    profile.emplace_back(radius * std::cos(a), half_length + radius * std::sin(a));
  }
  profile.front().first = 0;
  profile.back().first = 0;
  return revolve(profile, segments);
}

SurfaceMesh make_cylinder(double r, double half_height, int segments) {
  std::vector<std::pair<double, double>> profile;
  const double spacing = 2 * kPi * r / segments;
  const int cap_steps = std::max(1, static_cast<int>(std::ceil(r / spacing)));
  profile.emplace_back(0, -half_height);
  for (int i = 1; i <= cap_steps; ++i) profile.emplace_back(r * i / cap_steps, -half_height);
  const int body_steps = std::max(1, static_cast<int>(std::ceil(2 * half_height / spacing)));
  for (int i = 1; i < body_steps; ++i) profile.emplace_back(r, -half_height + 2 * half_height * i / body_steps);
  for (int i = cap_steps; i >= 1; --i) profile.emplace_back(r * i / cap_steps, half_height);
  profile.emplace_back(0, half_height);
  return revolve(profile, segments);
}

SurfaceMesh make_torus(double R, double r, int nu, int nv) {
  SurfaceMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
      m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  const auto id = [&](int i, int j) { return static_cast<Index>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

SurfaceMesh make_box(double ax, double ay, double az, int n) {
  SurfaceMesh m;
  std::map<std::array<long, 3>, Index> index;  // shared edge/corner vertices, by grid position
  const Vec3 half(ax, ay, az);
  const auto vertex = [&](const std::array<long, 3>& g) {
    auto [it, inserted] = index.try_emplace(g, 0);
    if (inserted) {
      m.vertices.emplace_back(half.x() * (2.0 * g[0] / n - 1), half.y() * (2.0 * g[1] / n - 1),
                              half.z() * (2.0 * g[2] / n - 1));
      it->second = static_cast<Index>(m.vertices.size() - 1);
    }
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<long, 3> g00{}, g10{}, g11{}, g01{};
          for (auto* g : {&g00, &g10, &g11, &g01}) (*g)[axis] = side ? n : 0;
          g00[u] = i, g00[v] = j;
          g10[u] = i + 1, g10[v] = j;
          g11[u] = i + 1, g11[v] = j + 1;
          g01[u] = i, g01[v] = j + 1;
          const Index a = vertex(g00), b = vertex(g10), c = vertex(g11), d = vertex(g01);
          // (u, v, axis) is right-handed, so u×v points along +axis: keep the order on the + side.
          if (side) {
            m.faces.push_back({a, b, c});
            m.faces.push_back({a, c, d});
          } else {
            m.faces.push_back({a, c, b});
            m.faces.push_back({a, d, c});
          }
        }
    }
  return m;
}

double sphere_axis_distance(const Vec3& p) { return p.norm(); }

double capsule_axis_distance(const Vec3& p, double half_length) {
  const double z = std::clamp(p.z(), -half_length, half_length);
  return (p - Vec3(0, 0, z)).norm();
}

double torus_axis_distance(const Vec3& p, double R) {
  const double rho = std::hypot(p.x(), p.y());
  return std::hypot(rho - R, p.z());
}

double ellipsoid_axis_distance(const Vec3& p, double a, double b, double c) {
  const double A = (a * a - c * c) / a, B = (b * b - c * c) / b;
  const double x = std::abs(p.x()), y = std::abs(p.y());
  if ((x * x) / (A * A) + (y * y) / (B * B) <= 1.0) return std::abs(p.z());
  // Closest point on the ellipse boundary: minimise over the angle by dense search + refinement.
  double best_t = 0, best = 1e300;
  const auto dist2 = [&](double t) { return std::pow(A * std::cos(t) - x, 2) + std::pow(B * std::sin(t) - y, 2); };
  for (int i = 0; i <= 256; ++i) {
    const double t = (kPi / 2) * i / 256;
    if (dist2(t) < best) best = dist2(t), best_t = t;
  }
  double lo = std::max(0.0, best_t - kPi / 512), hi = std::min(kPi / 2, best_t + kPi / 512);
  for (int it = 0; it < 100; ++it) {  // golden-section search on the bracket
    const double m1 = lo + (hi - lo) * 0.381966, m2 = lo + (hi - lo) * 0.618034;
    if (dist2(m1) < dist2(m2)) hi = m2;
    else lo = m1;
  }
  return std::sqrt(dist2(0.5 * (lo + hi)) + p.z() * p.z());
}

}  // namespace medax::testing
