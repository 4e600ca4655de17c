#include "primitive_template.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <utility>

namespace medax::msd {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// One closed ring of template vertices, sorted by the cyclic parameter u ∈ [0, 1) that pairs
/// corresponding points of neighbouring rings.
using Ring = std::vector<Index>;

class Builder {
 public:
  Builder(double radius, double theta) : radius_(radius), theta_(theta) {}

  Index add(const Vec3& base, const Vec3& direction, double u) {
    shape_.base.push_back(base);
    shape_.direction.push_back(direction.normalized());
    u_.push_back(u - std::floor(u));
    return static_cast<Index>(shape_.base.size() - 1);
  }
  Ring sorted(Ring ring) const {
    std::sort(ring.begin(), ring.end(), [&](Index a, Index b) { return u_[a] < u_[b]; });
    return ring;
  }
  void face(Index a, Index b, Index c) { shape_.faces.push_back({a, b, c}); }
  /// Triangulates the band between two rings, advancing along whichever ring's next point has
  /// the smaller parameter (a single-point ring gives a fan).
  void zip(const Ring& a, const Ring& b);
  /// Orients every face along its vertices' directions (all templates are star-shaped about P).
  PrimitiveTemplate finish();

  double radius() const { return radius_; }
  double theta() const { return theta_; }
  /// Intervals for an arc of `angle` at the template radius.
  int arc_intervals(double angle) const { return std::max(1, static_cast<int>(std::lround(angle / theta_))); }

 private:
  double unwrapped(const Ring& ring, std::size_t i) const {
    return u_[ring[i % ring.size()]] + static_cast<double>(i / ring.size());
  }
  double radius_, theta_;
  PrimitiveTemplate shape_;
  std::vector<double> u_;
};

void Builder::zip(const Ring& a, const Ring& b) {
  const std::size_t na = a.size() > 1 ? a.size() : 0, nb = b.size() > 1 ? b.size() : 0;
  std::size_t i = 0, j = 0;
  while (i < na || j < nb) {
    const bool advance_a = j >= nb || (i < na && unwrapped(a, i + 1) <= unwrapped(b, j + 1));
    if (advance_a) {
      face(a[i % a.size()], a[(i + 1) % a.size()], b[j % b.size()]);
      ++i;
    } else {
      face(a[i % a.size()], b[(j + 1) % b.size()], b[j % b.size()]);
      ++j;
    }
  }
}

PrimitiveTemplate Builder::finish() {
  const auto at = [&](Index v) { return Vec3(shape_.base[v] + radius_ * shape_.direction[v]); };
  for (Tri& f : shape_.faces) {
    const Vec3 normal = (at(f[1]) - at(f[0])).cross(at(f[2]) - at(f[0]));
    const Vec3 outward = shape_.direction[f[0]] + shape_.direction[f[1]] + shape_.direction[f[2]];
    if (normal.dot(outward) < 0) std::swap(f[1], f[2]);
  }
  return std::move(shape_);
}

/// Segments along a length at spacing θ·radius, capped.
int segments_along(double length, const Builder& builder, std::size_t max_segments) {
  const double n = std::ceil(length / (builder.theta() * builder.radius()));
  return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(max_segments)));
}

/// Sphere (p0 == p1) or capsule around the segment p0 p1: south pole, cap rings, the wall's
/// equator rings, cap rings, north pole. Rings alternate a half-step twist for better triangles.
void add_capsule(Builder& builder, const Vec3& p0, const Vec3& p1, std::size_t max_segments) {
  const double length = (p1 - p0).norm();
  const Vec3 axis = length > 0 ? Vec3((p1 - p0) / length) : Vec3::UnitZ();
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  const int quarter = std::max(2, builder.arc_intervals(kPi / 2));
  std::vector<Ring> rings;
  const auto ring_at = [&](const Vec3& base, double axial, double radial) {
    const int count = radial < 1e-12 ? 1 : std::max(3, builder.arc_intervals(2 * kPi * radial));
    const double twist = 0.5 * static_cast<double>(rings.size() % 2);
    Ring ring;
    for (int j = 0; j < count; ++j) {
      const double alpha = 2 * kPi * (j + (count > 1 ? twist : 0.0)) / count;
      const Vec3 d = axial * axis + radial * (std::cos(alpha) * e1 + std::sin(alpha) * e2);
      ring.push_back(builder.add(base, d, alpha / (2 * kPi)));
    }
    rings.push_back(builder.sorted(std::move(ring)));
  };
  for (int k = 0; k < quarter; ++k) {
    const double phi = kPi / 2 * k / quarter;  // from the south pole
    ring_at(p0, -std::cos(phi), std::sin(phi));
  }
  const int wall = length > 0 ? segments_along(length, builder, max_segments) : 0;
  for (int j = 0; j <= wall; ++j) ring_at(p0 + (length * j / std::max(wall, 1)) * axis, 0.0, 1.0);
  for (int k = quarter - 1; k >= 0; --k) {
    const double phi = kPi / 2 * k / quarter;
    ring_at(p1, std::cos(phi), std::sin(phi));
  }
  for (std::size_t r = 0; r + 1 < rings.size(); ++r) builder.zip(rings[r], rings[r + 1]);
}

/// The triangle's corners, unit normal, outward in-plane side normals ν_s (side s = c_s c_{s+1})
/// and exterior angles at c_{s+1}.
struct Slab {
  std::array<Vec3, 3> c;
  Vec3 normal;
  std::array<Vec3, 3> side_normal;
  std::array<double, 3> exterior;
  int segments = 1;  ///< per side
};

Slab make_slab(const SkeletonElement& element, const Builder& builder, std::size_t max_segments) {
  Slab slab;
  slab.c = element.corners;
  const Vec3 cross = (slab.c[1] - slab.c[0]).cross(slab.c[2] - slab.c[0]);
  double longest = 0;
  for (int s = 0; s < 3; ++s) longest = std::max(longest, (slab.c[(s + 1) % 3] - slab.c[s]).norm());
  if (cross.norm() <= 1e-12 * longest * longest)
    throw std::invalid_argument(fmt::format("degenerate skeleton triangle ({}, {}, {}): its corners are collinear",
                                            element.ids[0], element.ids[1], element.ids[2]));
  slab.normal = cross.normalized();
  for (int s = 0; s < 3; ++s) slab.side_normal[s] = (slab.c[(s + 1) % 3] - slab.c[s]).cross(slab.normal).normalized();
  for (int s = 0; s < 3; ++s)
    slab.exterior[s] = std::acos(std::clamp(slab.side_normal[s].dot(slab.side_normal[(s + 1) % 3]), -1.0, 1.0));
  slab.segments = segments_along(longest, builder, max_segments);
  return slab;
}

/// Parameter of point j of side s on a wall ring (the corner arcs take the rest of the cycle).
double side_u(int s, double fraction) { return (s + 0.1 + 0.8 * fraction) / 3.0; }

/// A planar copy of the triangle (direction ±normal) as a barycentric grid; returns its boundary
/// ring (corners at u = s/3).
Ring add_planar_copy(Builder& builder, const Slab& slab, double side) {
  const int n = slab.segments;
  const Vec3 d = side * slab.normal;
  std::map<std::pair<int, int>, Index> id;
  Ring boundary;
  const auto vertex = [&](int i, int j) { return Vec3(slab.c[0] + (slab.c[1] - slab.c[0]) * i / n + (slab.c[2] - slab.c[0]) * j / n); };
  const std::array<std::pair<int, int>, 3> start{{{0, 0}, {n, 0}, {0, n}}}, step{{{1, 0}, {-1, 1}, {0, -1}}};
  for (int s = 0; s < 3; ++s)
    for (int k = 0; k < n; ++k) {
      const int i = start[s].first + k * step[s].first, j = start[s].second + k * step[s].second;
      const double u = k == 0 ? s / 3.0 : side_u(s, static_cast<double>(k) / n);
      boundary.push_back(id[{i, j}] = builder.add(vertex(i, j), d, u));
    }
  for (int i = 1; i < n; ++i)
    for (int j = 1; i + j < n; ++j) id[{i, j}] = builder.add(vertex(i, j), d, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      builder.face(id[{i, j}], id[{i + 1, j}], id[{i, j + 1}]);
      if (i + j + 1 < n) builder.face(id[{i + 1, j}], id[{i + 1, j + 1}], id[{i, j + 1}]);
    }
  return builder.sorted(std::move(boundary));
}

/// The wall ring at height angle φ ∈ (−π/2, π/2): the three sides offset along ν_s and the
/// corner wedges' arcs.
Ring add_wall_ring(Builder& builder, const Slab& slab, double phi) {
  const int n = slab.segments;
  const double c = std::cos(phi), s_phi = std::sin(phi);
  Ring ring;
  for (int s = 0; s < 3; ++s) {
    const Vec3 &a = slab.c[s], &b = slab.c[(s + 1) % 3];
    for (int j = 0; j <= n; ++j)
      ring.push_back(builder.add(a + (b - a) * j / n, c * slab.side_normal[s] + s_phi * slab.normal,
                                 side_u(s, static_cast<double>(j) / n)));
    const double beta = slab.exterior[s];
    const Vec3 turn = slab.normal.cross(slab.side_normal[s]);
    const int arc = builder.arc_intervals(beta * c);
    for (int l = 1; l < arc; ++l) {
      const double t = static_cast<double>(l) / arc;
      const Vec3 in_plane = std::cos(beta * t) * slab.side_normal[s] + std::sin(beta * t) * turn;
      ring.push_back(builder.add(b, c * in_plane + s_phi * slab.normal, (s + 0.9 + 0.2 * t) / 3.0));
    }
  }
  return builder.sorted(std::move(ring));
}

void add_slab(Builder& builder, const SkeletonElement& element, std::size_t max_segments) {
  const Slab slab = make_slab(element, builder, max_segments);
  const int half = std::max(2, builder.arc_intervals(kPi / 2));
  Ring previous = add_planar_copy(builder, slab, -1.0);
  for (int k = 1; k < 2 * half; ++k) {
    Ring ring = add_wall_ring(builder, slab, -kPi / 2 + kPi * k / (2 * half));
    builder.zip(previous, ring);
    previous = std::move(ring);
  }
  builder.zip(previous, add_planar_copy(builder, slab, 1.0));
}

}  // namespace

PrimitiveTemplate make_template(const SkeletonElement& element, double radius, const TemplateOptions& options) {
  if (!(radius > 0)) throw std::invalid_argument(fmt::format("template radius {} is not positive", radius));
  Builder builder(radius, std::sqrt(4 * kPi / static_cast<double>(std::max<std::size_t>(options.sphere_vertices, 12))));
  switch (element.kind) {
    case ElementKind::Vertex:
      add_capsule(builder, element.corners[0], element.corners[0], options.max_segments);
      break;
    case ElementKind::Edge:
      if ((element.corners[1] - element.corners[0]).norm() <= 1e-9 * radius)
        throw std::invalid_argument(
            fmt::format("degenerate skeleton edge ({}, {}): its ends coincide", element.ids[0], element.ids[1]));
      add_capsule(builder, element.corners[0], element.corners[1], options.max_segments);
      break;
    case ElementKind::Triangle:
      add_slab(builder, element, options.max_segments);
      break;
  }
  return builder.finish();
}

std::vector<Segment> template_edges(const std::vector<Tri>& faces) {
  std::set<std::pair<Index, Index>> unique;
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) unique.emplace(std::minmax(f[k], f[(k + 1) % 3]));
  std::vector<Segment> edges;
  edges.reserve(unique.size());
  for (const auto& [a, b] : unique) edges.push_back({a, b});
  return edges;
}

Vec3 SkeletonElement::centre() const {
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < corner_count(); ++k) sum += corners[k];
  return sum / corner_count();
}

Vec3 SkeletonElement::closest_point(const Vec3& x) const {
  switch (kind) {
    case ElementKind::Vertex:
      return corners[0];
    case ElementKind::Edge: {
      const Vec3 &a = corners[0], &b = corners[1];
      const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      return a + t * (b - a);
    }
    case ElementKind::Triangle:
      break;
  }
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto point = [](const Vec3& p) { return K::Point_3(p.x(), p.y(), p.z()); };
  const K::Triangle_3 triangle(point(corners[0]), point(corners[1]), point(corners[2]));
  const K::Point_3 q = K().construct_projected_point_3_object()(triangle, point(x));
  return {q.x(), q.y(), q.z()};
}

std::vector<Vec3> primitive_vertices(const PrimitiveTemplate& shape, const std::vector<double>& r) {
  std::vector<Vec3> points(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) points[i] = shape.base[i] + r[i] * shape.direction[i];
  return points;
}

SurfaceMesh primitive_mesh(const Primitive& primitive) {
  return {primitive_vertices(primitive.shape, primitive.radius), primitive.shape.faces};
}

}  // namespace medax::msd
