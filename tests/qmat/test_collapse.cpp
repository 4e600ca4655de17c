// The Q-MAT collapse: topology with the checks on, error against the target, analytic shapes
// (sphere, capsule), saved vertices, determinism and scale invariance, the correction.
#include "collapse.hpp"
#include "correction.hpp"
#include "qmat_test_inputs.hpp"

#include <medax/services/envelope.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>
#include <medax/union_find.hpp>

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <set>

using namespace medax;
using namespace medax::qmat;

namespace {

QmatOptions to(std::size_t target) {
  QmatOptions o;
  o.target_vertices = target;
  return o;
}

/// Largest distance from a surface vertex to the boundary of the complex's envelope (the
/// surface side of the reconstruction error, the one the slab quadrics measure), at a resolution
/// of 1% of the bbox diagonal.
double surface_to_envelope(const MedialComplex& medial, const SurfaceMesh& surface) {
  const services::Envelope envelope(medial);
  const services::EnvelopeSamples samples = envelope.sample_boundary(0.01 * bbox_diagonal(surface.vertices));
  double worst = 0;
  for (double d : envelope.boundary_distances(surface.vertices, samples)) worst = std::max(worst, d);
  return worst;
}

/// Complexes are equal element by element (centres and radii up to `tolerance`).
void check_same(const MedialComplex& a, const MedialComplex& b, double scale, double tolerance) {
  REQUIRE(a.num_vertices() == b.num_vertices());
  CHECK(a.edges == b.edges);
  CHECK(a.faces == b.faces);
  for (std::size_t v = 0; v < a.num_vertices(); ++v) {
    CHECK((scale * a.centres[v] - b.centres[v]).norm() <= tolerance);
    CHECK(std::abs(scale * a.radii[v] - b.radii[v]) <= tolerance);
  }
}

/// The output is a valid complex: face edges present, no duplicates, radii > 0.
void check_valid(const MedialComplex& m) {
  REQUIRE_NOTHROW(m.validate());
  std::set<Segment> edges;
  for (Segment e : m.edges) {
    CHECK(e[0] < e[1]);
    CHECK(edges.insert(e).second);
  }
  std::set<Tri> faces;
  for (const Tri& t : m.faces) {
    Tri s = t;
    std::sort(s.begin(), s.end());
    CHECK(faces.insert(s).second);
    CHECK((s[0] < s[1] && s[1] < s[2]));
    for (int k = 0; k < 3; ++k) {
      const Index a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      CHECK(edges.count({a, b}) == 1);
    }
  }
  for (double r : m.radii) CHECK(r > 0);
}

/// The complex scaled about the origin.
MedialComplex scaled(MedialComplex m, double scale) {
  for (auto& c : m.centres) c *= scale;
  for (auto& r : m.radii) r *= scale;
  return m;
}

}  // namespace

TEST_CASE("with the link condition, the simplified complex keeps the input's Euler characteristic and Betti "
          "numbers",
          "[qmat][collapse]") {
  for (const char* file : {"ellipsoid.off", "joint.off"}) {
    INFO(file);
    const MedialComplex axis = test::voronoi_axis(file);
    QmatOptions o = to(50);
    o.link_condition = true;  // the topology guard stays on (its default)
    QmatReport report;
    const MedialComplex out = simplify(axis, {}, o, &report);
    check_valid(out);
    const auto before = services::complex_topology(axis), after = services::complex_topology(out);
    CHECK(out.num_vertices() < axis.num_vertices() / 4);
    CHECK(after.euler == before.euler);
    CHECK(after.b0 == before.b0);
    CHECK(after.b1 == before.b1);
    CHECK(after.b2 == before.b2);
  }
}

TEST_CASE("the reconstruction error grows as the target count falls", "[qmat][collapse]") {
  // The ellipsoid: the raw Voronoi axis of a coarse mesh pokes out of the shape, so the first
  // collapses lower the error; from 200 vertices on it grows.
  const SurfaceMesh ellipsoid = read_mesh(test::data_dir() / "ellipsoid.off");
  const MedialComplex axis = test::voronoi_axis(ellipsoid);
  REQUIRE(axis.num_vertices() > 200);
  std::vector<double> errors;
  for (std::size_t target : {200, 100, 50, 25, 12}) {
    const MedialComplex out = simplify(axis, {}, to(target), nullptr);
    check_valid(out);
    CHECK(out.num_vertices() == target);
    errors.push_back(surface_to_envelope(out, ellipsoid));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    INFO("target step " << k << ": " << errors[k - 1] << " -> " << errors[k]);
    CHECK(errors[k] >= errors[k - 1]);
  }
  CHECK(errors.back() > 3 * errors.front());
}

TEST_CASE("a sphere's Voronoi axis collapses to one vertex of radius R at the centre", "[qmat][collapse]") {
  const SurfaceMesh sphere = read_mesh(test::data_dir() / "sphere.obj");
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : sphere.vertices) centre += p;
  centre /= double(sphere.vertices.size());
  double radius = 0;
  for (const Vec3& p : sphere.vertices) radius += (p - centre).norm();
  radius /= double(sphere.vertices.size());
  const MedialComplex axis = test::voronoi_axis(sphere);
  REQUIRE(axis.num_vertices() > 10);
  // The guard keeps curve tips, and the Voronoi axis of a sampled sphere is a cluster of nearly
  // coincident vertices joined by tiny edges: it would stop at a few of them.
  QmatOptions o = to(1);
  o.topology_guard = false;
  const MedialComplex out = simplify(axis, {}, o, nullptr);
  REQUIRE(out.num_vertices() == 1);
  CHECK((out.centres[0] - centre).norm() <= 0.02 * radius);
  CHECK(out.radii[0] == Approx(radius).epsilon(0.02));
}

TEST_CASE("a capsule's Voronoi axis collapses to a segment of spheres of the capsule's radius", "[qmat][collapse]") {
  const double radius = 0.5, half_length = 1.0;
  const SurfaceMesh capsule = testing::make_capsule(radius, half_length, 24);
  const MedialComplex axis = test::voronoi_axis(capsule);
  // Each cap's Voronoi vertices are a star of tiny tips at the cap centre, which the guard keeps.
  QmatOptions o = to(8);
  o.topology_guard = false;
  const MedialComplex out = simplify(axis, {}, o, nullptr);
  check_valid(out);
  REQUIRE(out.num_vertices() == 8);
  double lowest = 1e9, highest = -1e9;
  for (std::size_t v = 0; v < out.num_vertices(); ++v) {
    const Vec3& c = out.centres[v];
    CHECK(c.head<2>().norm() <= 0.15 * radius);  // on the axis (the caps are rotationally degenerate)
    CHECK(std::abs(c.z()) <= half_length + 0.05 * radius);
    CHECK(out.radii[v] == Approx(radius).epsilon(0.05));
    lowest = std::min(lowest, c.z());
    highest = std::max(highest, c.z());
  }
  CHECK(highest - lowest >= 1.5 * half_length);  // spans the segment
  const auto topology = services::complex_topology(out);
  CHECK(topology.b0 == 1);
  CHECK(topology.b1 == 0);
  CHECK(topology.b2 == 0);
  CHECK(out.edges.size() == out.num_vertices() - 1);  // a tree of segments
}

TEST_CASE("saved vertices survive unchanged; one leftover per component without a saved vertex",
          "[qmat][collapse][saved]") {
  for (const char* file : {"ellipsoid.off", "joint.off"}) {
    INFO(file);
    const MedialComplex axis = test::voronoi_axis(file);
    std::vector<char> saved(axis.num_vertices(), 0);
    for (std::size_t v = 0; v < axis.num_vertices(); v += axis.num_vertices() / 12) saved[v] = 1;
    const std::size_t n_saved = std::count(saved.begin(), saved.end(), 1);
    // Components without a saved vertex.
    UnionFind components(axis.num_vertices());
    for (const Segment& e : axis.edges) components.unite(e[0], e[1]);
    for (const Tri& t : axis.faces) components.unite(t[0], t[1]), components.unite(t[1], t[2]);
    std::set<Index> roots, saved_roots;
    for (Index v = 0; v < axis.num_vertices(); ++v) {
      roots.insert(components.find(v));
      if (saved[v]) saved_roots.insert(components.find(v));
    }
    const MedialComplex out = simplify(axis, saved, to(n_saved), nullptr);
    check_valid(out);
    CHECK(out.num_vertices() == n_saved + roots.size() - saved_roots.size());
    std::set<std::array<double, 4>> kept;
    for (std::size_t v = 0; v < out.num_vertices(); ++v)
      kept.insert({out.centres[v].x(), out.centres[v].y(), out.centres[v].z(), out.radii[v]});
    for (Index v = 0; v < axis.num_vertices(); ++v) {
      if (!saved[v]) continue;
      bool found = false;
      for (const auto& s : kept)
        found = found || ((Vec3(s[0], s[1], s[2]) - axis.centres[v]).norm() <= 1e-12 &&
                          std::abs(s[3] - axis.radii[v]) <= 1e-12);
      CHECK(found);
    }
  }
}

TEST_CASE("deterministic, and invariant to a uniform scale of the input", "[qmat][collapse]") {
  const SurfaceMesh joint = read_mesh(test::data_dir() / "joint.off");
  const MedialComplex axis = test::voronoi_axis(joint);
  const MedialComplex once = simplify(axis, {}, to(60), nullptr);
  const MedialComplex twice = simplify(axis, {}, to(60), nullptr);
  check_same(once, twice, 1.0, 0.0);
  // A power of two scales every number exactly: the same collapses, bit for bit.
  check_same(once, simplify(scaled(axis, 4.0), {}, to(60), nullptr), 4.0, 0.0);
  // Another factor rounds differently, which may reorder near-ties: the same count and error.
  const MedialComplex by3 = simplify(scaled(axis, 3.0), {}, to(60), nullptr);
  CHECK(by3.num_vertices() == once.num_vertices());
  const double error = surface_to_envelope(once, joint), error3 = surface_to_envelope(scaled(by3, 1.0 / 3.0), joint);
  CHECK(error3 == Approx(error).epsilon(0.25));
}

TEST_CASE("the first costing in parallel gives the sequential result bit for bit, whatever the thread count",
          "[qmat][collapse]") {
  const MedialComplex axis = test::voronoi_axis("torus.obj");
  REQUIRE(axis.num_vertices() > 4000);  // several blocks of the parallel costing
  QmatOptions sequential = to(80);
  sequential.parallel = false;
  const MedialComplex reference = simplify(axis, {}, sequential, nullptr);
  for (int threads : {1, 2, 3}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    check_same(simplify(axis, {}, to(80), nullptr), reference, 1.0, 0.0);
  }
}

TEST_CASE("the shrinking-ball correction moves perturbed spheres back onto a capsule's axis",
          "[qmat][correction]") {
  const double radius = 0.5, half_length = 1.0;
  const SurfaceMesh capsule = testing::make_capsule(radius, half_length, 48);
  MedialComplex spheres;
  for (int k = 0; k < 5; ++k) spheres.add_vertex(Vec3(0.1, -0.05, -0.6 + 0.3 * k), 0.3);
  const CorrectionReport report = shrinking_ball_correction(spheres, capsule);
  CHECK(report.corrected == 5);
  for (std::size_t v = 0; v < spheres.num_vertices(); ++v) {
    CHECK(spheres.centres[v].head<2>().norm() <= 0.05);
    CHECK(spheres.radii[v] == Approx(radius).epsilon(0.05));
  }
}

TEST_CASE("max_cost stops before the first dearer collapse; parity mode still keeps the saved count",
          "[qmat][collapse]") {
  const MedialComplex axis = test::voronoi_axis("ellipsoid.off");
  QmatReport to_target;
  simplify(axis, {}, to(40), &to_target);
  REQUIRE(to_target.stopped_by == "target");
  QmatOptions bounded;
  bounded.max_cost = 0.5 * to_target.last_cost;
  QmatReport report;
  const MedialComplex out = simplify(axis, {}, bounded, &report);
  check_valid(out);
  CHECK(report.stopped_by == "max_cost");
  CHECK(report.last_cost <= bounded.max_cost);
  CHECK(out.num_vertices() > 40);

  std::vector<char> saved(axis.num_vertices(), 0);
  for (std::size_t v = 0; v < axis.num_vertices(); v += 50) saved[v] = 1;
  const std::size_t n_saved = std::count(saved.begin(), saved.end(), 1);
  QmatOptions parity = to(n_saved);
  parity.stale_saved_costs = true;
  const MedialComplex stale = simplify(axis, saved, parity, nullptr);
  check_valid(stale);
  CHECK(stale.num_vertices() == n_saved);  // one component, every vertex collapses onto a saved one
}
