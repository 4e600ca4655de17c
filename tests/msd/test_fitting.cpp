// MSD primitive templates and local fitting (plugins/msd: primitive_template, fitting,
// target_mesh) on analytic shapes: notes §7 items 4, 5, 7, 8.
#include "fitting.hpp"
#include "mesh_checks.hpp"

#include <medax/io.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <random>

using namespace medax;
using namespace medax::msd;
using medax::msd::checks::check_closed_manifold;
using medax::msd::checks::winding;
using medax::testing::make_box;
using medax::testing::make_capsule;
using medax::testing::make_sphere;

namespace {

SkeletonElement vertex_element(const Vec3& p) { return {ElementKind::Vertex, {0, 0, 0}, {p, p, p}}; }
SkeletonElement edge_element(const Vec3& a, const Vec3& b) { return {ElementKind::Edge, {0, 1, 0}, {a, b, b}}; }
SkeletonElement triangle_element(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {ElementKind::Triangle, {0, 1, 2}, {a, b, c}};
}

/// Closest point of the element (vertex, segment or triangle) to p.
Vec3 closest_on_element(const SkeletonElement& e, const Vec3& p) {
  const auto on_segment = [](const Vec3& a, const Vec3& b, const Vec3& q) {
    const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    return Vec3(a + t * (b - a));
  };
  if (e.kind == ElementKind::Vertex) return e.corners[0];
  if (e.kind == ElementKind::Edge) return on_segment(e.corners[0], e.corners[1], p);
  const Vec3 &a = e.corners[0], &b = e.corners[1], &c = e.corners[2];
  const Vec3 n = (b - a).cross(c - a).normalized();
  const Vec3 q = p - (p - a).dot(n) * n;
  const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return q;
  Vec3 best = on_segment(a, b, p);
  for (const Vec3& x : {on_segment(b, c, p), on_segment(c, a, p)})
    if ((x - p).norm() < (best - p).norm()) best = x;
  return best;
}

/// Number of faces the ray o + s d (s > 0) crosses.
int crossings(const std::vector<Vec3>& v, const std::vector<Tri>& faces, const Vec3& o, const Vec3& d) {
  int count = 0;
  for (const Tri& f : faces) {
    const Vec3 e1 = v[f[1]] - v[f[0]], e2 = v[f[2]] - v[f[0]], h = d.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-300) continue;
    const Vec3 s = o - v[f[0]];
    const double u = s.dot(h) / det, w = d.dot(s.cross(e1)) / det, t = e2.dot(s.cross(e1)) / det;
    if (u >= 0 && w >= 0 && u + w <= 1 && t > 0) ++count;
  }
  return count;
}

/// Rays through face centres (base and direction averaged over the face) each cross T_P once.
void check_consistent(const Primitive& p) {
  const std::vector<Vec3> x = primitive_vertices(p.shape, p.radius);
  int bad = 0;
  for (std::size_t k = 0; k < p.shape.faces.size(); k += 17) {
    const Tri& f = p.shape.faces[k];
    const Vec3 b = (p.shape.base[f[0]] + p.shape.base[f[1]] + p.shape.base[f[2]]) / 3;
    const Vec3 d = (p.shape.direction[f[0]] + p.shape.direction[f[1]] + p.shape.direction[f[2]]).normalized();
    if (crossings(x, p.shape.faces, b, d) != 1) ++bad;
  }
  CHECK(bad == 0);
}

void check_fitted(const Primitive& p) {
  REQUIRE(p.fitted);
  REQUIRE(p.radius.size() == p.shape.size());
  check_closed_manifold(p.shape.faces, p.shape.size());
  std::size_t nonpositive = 0, penetrating = 0;
  for (std::size_t i = 0; i < p.radius.size(); ++i) {
    nonpositive += !(p.radius[i] > 0);
    penetrating += p.radius[i] > p.max_radius[i] + 1e-9;
  }
  CHECK(nonpositive == 0);
  CHECK(penetrating == 0);
  // The element lies inside its primitive (its corners and centre, moved a hair inward).
  const std::vector<Vec3> x = primitive_vertices(p.shape, p.radius);
  const Vec3 centre = p.element.centre();
  for (int k = 0; k < p.element.corner_count(); ++k)
    CHECK(winding(x, p.shape.faces, p.element.corners[k] + 1e-6 * (centre - p.element.corners[k])) ==
          Approx(1.0).margin(1e-6));
  CHECK(winding(x, p.shape.faces, centre) == Approx(1.0).margin(1e-6));
  check_consistent(p);
}

const std::vector<SkeletonElement>& sample_elements() {
  static const std::vector<SkeletonElement> elements{
      vertex_element({0.1, -0.2, 0.05}), edge_element({-0.5, 0, 0}, {0.4, 0.2, 0.1}),
      triangle_element({-0.5, -0.4, 0}, {0.5, -0.3, 0.05}, {0.0, 0.5, -0.05}),
      triangle_element({-0.6, 0, 0}, {0.6, 0, 0}, {0.5, 0.1, 0})};  // obtuse
  return elements;
}

}  // namespace

TEST_CASE("msd templates: closed 2-manifolds, unit directions, bases on the element, the medial primitive at constant r") {
  for (const SkeletonElement& e : sample_elements()) {
    const PrimitiveTemplate t = make_template(e, 0.2);
    INFO("kind " << e.corner_count() << ", " << t.size() << " vertices");
    check_closed_manifold(t.faces, t.size());
    const double r = 0.37;  // any constant: the vertices sit at distance r from P (Def. 4.1)
    const std::vector<Vec3> x = primitive_vertices(t, std::vector<double>(t.size(), r));
    double worst_direction = 0, worst_base = 0, worst_distance = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      worst_direction = std::max(worst_direction, std::abs(t.direction[i].norm() - 1));
      worst_base = std::max(worst_base, (closest_on_element(e, t.base[i]) - t.base[i]).norm());
      worst_distance = std::max(worst_distance, std::abs((closest_on_element(e, x[i]) - x[i]).norm() - r));
    }
    CHECK(worst_direction < 1e-12);
    CHECK(worst_base < 1e-12);
    CHECK(worst_distance < 1e-12);
    // Outward: positive enclosed volume.
    double volume = 0;
    for (const Tri& f : t.faces) volume += x[f[0]].dot(x[f[1]].cross(x[f[2]])) / 6;
    CHECK(volume > 0);
  }
  // The paper's vertex template has 1,588 vertices; ours is within a few percent.
  CHECK(make_template(sample_elements()[0], 1.0).size() == Approx(1588).epsilon(0.05));
}

TEST_CASE("msd fitting: a vertex at the centre of a sphere reaches the sphere") {
  const double R = 1.0;
  const TargetMesh sphere(make_sphere(R, 5));
  const Primitive p = fit_primitive(sphere, vertex_element(Vec3::Zero()));
  check_fitted(p);
  // Tessellation error of a level-5 icosphere: the inscribed distance is within 1e-3 of R.
  for (std::size_t i = 0; i < p.radius.size(); ++i) REQUIRE(p.radius[i] == Approx(R).margin(2e-3));
}

TEST_CASE("msd fitting: an edge on the axis of a capsule reproduces the capsule") {
  const double r = 0.3, half = 1.0;
  const TargetMesh capsule(make_capsule(r, half, 96));
  const Primitive p = fit_primitive(capsule, edge_element({0, 0, -half}, {0, 0, half}));
  check_fitted(p);
  const std::vector<Vec3> x = primitive_vertices(p.shape, p.radius);
  double worst = 0;
  for (const Vec3& v : x) worst = std::max(worst, std::abs(medax::testing::capsule_axis_distance(v, half) - r));
  CHECK(worst < 2e-3 * r);
}

TEST_CASE("msd fitting: primitives in a box stay inside, are consistent, and contain their element") {
  const TargetMesh box(make_box(1.0, 0.8, 0.6, 12));
  for (const SkeletonElement& e : sample_elements()) {
    const Primitive p = fit_primitive(box, e);
    INFO("kind " << e.corner_count());
    check_fitted(p);
    // The box is not a sphere: the primitive grew beyond ρ0 toward the walls.
    CHECK(*std::max_element(p.radius.begin(), p.radius.end()) > 1.5 * p.initial_radius);
  }
}

TEST_CASE("msd fitting: with a huge expansion weight and no contact the radii follow the target") {
  const PrimitiveTemplate t = make_template(sample_elements()[2], 0.1);
  FitOptions options;
  options.expansion = 1e9;
  RadiusSolver solver(t.faces, std::vector<double>(t.size(), 1e6), options, 1e-12);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(0.5, 2.0);
  Eigen::VectorXd target(static_cast<Eigen::Index>(t.size()));
  for (Eigen::Index i = 0; i < target.size(); ++i) target[i] = uniform(random);
  Eigen::VectorXd radius = Eigen::VectorXd::Ones(target.size());
  solver.solve(target, radius);
  CHECK((radius - target).lpNorm<Eigen::Infinity>() < 1e-6);
  // With the paper's w = 10 the same target is smoothed ((L + wI)⁻¹w damps every non-constant
  // mode): the radii vary clearly less than the random target.
  RadiusSolver smooth(t.faces, std::vector<double>(t.size(), 1e6), FitOptions{}, 1e-12);
  Eigen::VectorXd smoothed = Eigen::VectorXd::Ones(target.size());
  smooth.solve(target, smoothed);
  const auto spread = [](const Eigen::VectorXd& v) { return (v.array() - v.mean()).matrix().norm(); };
  CHECK(spread(smoothed) < 0.8 * spread(target));
}

TEST_CASE("msd fitting: the contact penalty and the clamp keep every radius below its first hit") {
  // A box much smaller than the growth: the targets overshoot, the penalty holds them back.
  const TargetMesh box(make_box(0.3, 0.3, 0.3, 6));
  FitOptions options;
  options.step_fraction = 0.5;
  const Primitive p = fit_primitive(box, vertex_element({0.05, 0.02, -0.03}), options);
  check_fitted(p);
  std::size_t touching = 0;
  for (std::size_t i = 0; i < p.radius.size(); ++i) touching += p.radius[i] > p.max_radius[i] - 1e-3;
  CHECK(touching > p.radius.size() / 2);
}

TEST_CASE("msd fitting with the authors' neighbour cap keeps the invariants and grows no further") {
  const TargetMesh box(make_box(1.0, 0.8, 0.6, 12));
  FitOptions capped;
  capped.neighbour_cap = true;
  for (const SkeletonElement& e : sample_elements()) {
    INFO("kind " << e.corner_count());
    const Primitive paper = fit_primitive(box, e), authors = fit_primitive(box, e, capped);
    check_fitted(authors);
    double sum_paper = 0, sum_authors = 0;
    for (std::size_t i = 0; i < paper.radius.size(); ++i) {
      sum_paper += paper.radius[i];
      sum_authors += authors.radius[i];
    }
    CHECK(sum_authors <= sum_paper * (1 + 1e-9));
  }
}

TEST_CASE("msd fitting is scale covariant") {
  const double s = 3.7;
  const Vec3 shift(1.5, -2.0, 0.25);
  SurfaceMesh mesh = make_box(1.0, 0.8, 0.6, 10), scaled = mesh;
  for (Vec3& v : scaled.vertices) v = s * v + shift;
  const TargetMesh a(mesh), b(scaled);
  const SkeletonElement e = sample_elements()[1];
  SkeletonElement moved = e;
  for (Vec3& c : moved.corners) c = s * c + shift;
  const Primitive pa = fit_primitive(a, e), pb = fit_primitive(b, moved);
  REQUIRE(pa.fitted);
  REQUIRE(pb.fitted);
  REQUIRE(pa.radius.size() == pb.radius.size());
  for (std::size_t i = 0; i < pa.radius.size(); ++i) REQUIRE(pb.radius[i] == Approx(s * pa.radius[i]).epsilon(1e-6));
}

TEST_CASE("msd fitting gives identical primitives across thread counts") {
  const TargetMesh box(make_box(1.0, 0.8, 0.6, 12));
  const auto run_with = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    tbb::task_arena arena(threads);
    return arena.execute([&] { return fit_primitives(box, sample_elements()); });
  };
  const std::vector<Primitive> one = run_with(1), two = run_with(2);
  REQUIRE(one.size() == two.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    CHECK(one[k].radius == two[k].radius);
    CHECK(one[k].shape.faces == two[k].shape.faces);
  }
}

TEST_CASE("msd fitting reports an element outside the shape instead of fitting it") {
  const TargetMesh sphere(make_sphere(1.0, 3));
  const Primitive p = fit_primitive(sphere, vertex_element({3, 0, 0}));
  CHECK_FALSE(p.fitted);
  CHECK(p.failure.find("never leave") != std::string::npos);
  const Primitive degenerate = fit_primitive(sphere, edge_element({0.1, 0, 0}, {0.1, 0, 0}));
  CHECK_FALSE(degenerate.fitted);
  CHECK(degenerate.failure.find("degenerate") != std::string::npos);
}

TEST_CASE("msd fitting on a real mesh (joint.off): vertex primitives at mid-thickness points keep every invariant") {
  const SurfaceMesh mesh = read_mesh(MEDAX_TEST_DATA_DIR "/joint.off");
  const TargetMesh target(mesh);
  std::vector<Vec3> normals(mesh.vertices.size(), Vec3::Zero());
  for (const Tri& f : mesh.faces) {
    const Vec3 n = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    for (const Index v : f) normals[v] += n;
  }
  std::vector<SkeletonElement> elements;
  for (const Index v : {0u, 55u, 110u, 165u}) {
    // Half-way along the inward normal to the opposite wall: a point inside the solid.
    const Vec3 inward = -normals[v].normalized();
    const auto thickness = target.first_exit(mesh.vertices[v] + 1e-9 * target.scale() * inward, inward);
    REQUIRE(thickness);
    elements.push_back(vertex_element(mesh.vertices[v] + 0.5 * *thickness * inward));
  }
  const std::vector<Primitive> primitives = fit_primitives(target, elements);
  for (const Primitive& p : primitives) check_fitted(p);
}
