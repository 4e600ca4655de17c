// The interior Voronoi diagram on analytic shapes with known medial axes, and its structure on
// a real mesh: generators equidistant at the radius, edges and faces dual to Delaunay facets
// and edges, determinism, and the same result with either inside test.
#include "interior_voronoi.hpp"

#include <medax/io.hpp>
#include <medax/testing/shapes.hpp>

#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <set>

using namespace medax;
using voronoi::interior_voronoi;

namespace {

constexpr double kPi = 3.14159265358979323846;

double quantile(std::vector<double> v, double q) {
  REQUIRE(!v.empty());
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

/// Every vertex has 4 distinct, sorted generators, all at the radius from the centre.
void check_generators(const MedialComplex& m, const std::vector<Vec3>& points, const std::string& kind) {
  CHECK(m.generator_kind == kind);
  REQUIRE(m.generators.size() == m.num_vertices());
  double scale = 0;
  for (const Vec3& p : points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    const auto& g = m.generators[i];
    REQUIRE(g.size() == 4);
    CHECK(std::is_sorted(g.begin(), g.end()));
    CHECK(std::adjacent_find(g.begin(), g.end()) == g.end());
    for (Index p : g) {
      REQUIRE(p < points.size());
      if (std::abs((points[p] - m.centres[i]).norm() - m.radii[i]) > 1e-9 * (scale + m.radii[i])) ++bad;
    }
  }
  CHECK(bad == 0);
}

std::size_t shared(const std::vector<Index>& a, const std::vector<Index>& b) {
  std::size_t n = 0;
  for (Index x : a) n += std::count(b.begin(), b.end(), x);
  return n;
}

/// Voronoi edges join cells sharing a Delaunay facet (3 generators); fan diagonals and face
/// corners share the Delaunay edge their polygon is dual to (2 generators); every face edge is
/// an edge, no edge twice.
void check_structure(const MedialComplex& m) {
  REQUIRE_NOTHROW(m.validate());
  const auto& g = m.generators;
  const auto& diagonal = m.edge_props.labels.get("fan_diagonal");
  REQUIRE(diagonal.size() == m.edges.size());
  std::set<std::pair<Index, Index>> edges;
  for (std::size_t e = 0; e < m.edges.size(); ++e) {
    const auto [a, b] = m.edges[e];
    CHECK(a < b);
    CHECK(edges.insert({a, b}).second);
    CHECK(shared(g[a], g[b]) == (diagonal[e] ? 2u : 3u));
  }
  const auto& polygon = m.face_props.labels.get("polygon");
  REQUIRE(polygon.size() == m.faces.size());
  std::map<int, std::vector<Index>> dual_edge;  // polygon -> the Delaunay edge (2 generators)
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const auto [a, b, c] = m.faces[f];
    for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, c}, std::pair{a, c}})
      CHECK(edges.count(std::minmax(x, y)) == 1);
    std::vector<Index> common;
    for (Index p : g[a])
      if (std::count(g[b].begin(), g[b].end(), p) && std::count(g[c].begin(), g[c].end(), p)) common.push_back(p);
    CHECK(common.size() == 2);
    auto [it, fresh] = dual_edge.emplace(polygon[f], common);
    if (!fresh) CHECK(it->second == common);
    if (f > 0) CHECK((polygon[f] == polygon[f - 1] || polygon[f] == polygon[f - 1] + 1));
  }
  MedialComplex closed = m;
  CHECK(closed.close_edges() == 0);
}

/// Connected components of the complex's vertices through its edges.
std::size_t components(const MedialComplex& m) {
  std::vector<Index> parent(m.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<Index(Index)> find = [&](Index x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  for (const auto& [a, b] : m.edges) parent[find(a)] = find(b);
  std::size_t n = 0;
  for (Index i = 0; i < parent.size(); ++i) n += find(i) == i;
  return n;
}

/// For every vertex: r ≥ the distance from the centre to the analytic surface (its generators
/// are on it), and not more than `slack` above (the ball may bulge between samples).
void check_radii(const MedialComplex& m, const std::function<double(const Vec3&)>& surface_distance, double slack) {
  std::size_t below = 0, above = 0;
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    const double d = surface_distance(m.centres[i]);
    CHECK(d > 0);  // strictly inside
    below += m.radii[i] < d - 1e-9;
    above += m.radii[i] > d + slack;
  }
  CHECK(below == 0);
  CHECK(above == 0);
}

}  // namespace

TEST_CASE("Voronoi of an icosphere: every vertex at the centre with radius R", "[voronoi]") {
  const SurfaceMesh sphere = testing::make_sphere(1.0, 3);
  voronoi::InteriorVoronoiReport report;
  const MedialComplex m = interior_voronoi(sphere.vertices, sphere, {}, &report);
  REQUIRE(m.num_vertices() > 100);
  CHECK(report.points == sphere.vertices.size());
  CHECK(report.interior == m.num_vertices());
  // The vertices are cospherical: every Delaunay cell's circumcentre is the centre.
  CHECK(report.interior == report.cells);
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    CHECK(m.centres[i].norm() < 1e-9);
    CHECK(m.radii[i] == Approx(1.0).epsilon(1e-12));
  }
  check_generators(m, sphere.vertices, "mesh_vertex");
  check_structure(m);
}

TEST_CASE("Voronoi of a capsule: vertices on the core segment", "[voronoi]") {
  const double R = 0.5, L = 1.0;
  const SurfaceMesh capsule = testing::make_capsule(R, L, 32);
  const MedialComplex m = interior_voronoi(capsule.vertices, capsule);
  REQUIRE(m.num_vertices() > 100);
  std::vector<double> axis;
  for (const Vec3& c : m.centres) axis.push_back(testing::capsule_axis_distance(c, L));
  // The bulk on the segment; a few vertices of flat cells near the surface are the discrete
  // Voronoi diagram's usual spikes.
  CHECK(quantile(axis, 0.5) < 1e-9);
  CHECK(quantile(axis, 0.75) < 0.02 * R);
  const double spacing = 2 * kPi * R / 32;
  check_radii(m, [&](const Vec3& c) { return R - testing::capsule_axis_distance(c, L); }, spacing);
  check_generators(m, capsule.vertices, "mesh_vertex");
  check_structure(m);
  CHECK(components(m) == 1);
}

TEST_CASE("Voronoi of a cylinder: the central part is the axis", "[voronoi]") {
  const double R = 0.5, H = 2.0;
  const SurfaceMesh cylinder = testing::make_cylinder(R, H, 32);
  const MedialComplex m = interior_voronoi(cylinder.vertices, cylinder);
  // Near the caps the medial axis has cone sheets; away from them (|z| < H - R) it is the axis.
  std::vector<double> central;
  for (const Vec3& c : m.centres)
    if (std::abs(c.z()) < H - 2 * R) central.push_back(std::hypot(c.x(), c.y()));
  REQUIRE(central.size() > 100);
  CHECK(quantile(central, 0.5) < 1e-9);
  CHECK(quantile(central, 0.9) < 0.02 * R);
  const double spacing = 2 * kPi * R / 32;
  check_radii(m, [&](const Vec3& c) { return std::min(R - std::hypot(c.x(), c.y()), H - std::abs(c.z())); },
              spacing);
  check_generators(m, cylinder.vertices, "mesh_vertex");
  check_structure(m);
}

TEST_CASE("Voronoi of a torus: connected, vertices around the whole core circle", "[voronoi]") {
  const double R = 2.0, r = 0.5;
  const SurfaceMesh torus = testing::make_torus(R, r, 64, 16);
  const MedialComplex m = interior_voronoi(torus.vertices, torus);
  REQUIRE(m.num_vertices() > 100);
  std::vector<double> core;
  std::vector<int> sectors(36, 0);
  for (const Vec3& c : m.centres) {
    const double d = testing::torus_axis_distance(c, R);
    core.push_back(d);
    if (d < 0.05 * r) {
      const double angle = std::atan2(c.y(), c.x()) + kPi;
      ++sectors[std::min(35, static_cast<int>(angle / (2 * kPi) * 36))];
    }
  }
  CHECK(quantile(core, 0.5) < 0.02 * r);
  CHECK(quantile(core, 0.75) < 0.2 * r);
  // Every 10° of the core circle has vertices on it, and the complex is one piece: it goes
  // around the hole (b1 ≥ 1 of the shape is represented).
  for (int s = 0; s < 36; ++s) CHECK(sectors[s] > 0);
  CHECK(components(m) == 1);
  check_radii(m, [&](const Vec3& c) { return r - testing::torus_axis_distance(c, R); }, 2 * kPi * r / 16);
  check_generators(m, torus.vertices, "mesh_vertex");
  check_structure(m);
}

TEST_CASE("Voronoi of a box: vertices equidistant from two faces, radius the distance to the box",
          "[voronoi]") {
  const Vec3 a(1.0, 0.5, 0.25);
  const SurfaceMesh box = testing::make_box(a.x(), a.y(), a.z(), 8);
  const MedialComplex m = interior_voronoi(box.vertices, box);
  REQUIRE(m.num_vertices() > 100);
  // On the box's medial axis the two nearest faces are at the same distance.
  std::vector<double> gap;
  for (const Vec3& c : m.centres) {
    std::array<double, 6> d{a.x() - c.x(), a.x() + c.x(), a.y() - c.y(), a.y() + c.y(), a.z() - c.z(), a.z() + c.z()};
    std::sort(d.begin(), d.end());
    gap.push_back(d[1] - d[0]);
  }
  CHECK(quantile(gap, 0.5) < 1e-12);
  CHECK(quantile(gap, 1.0) < 0.5 * a.z());
  check_radii(m, [&](const Vec3& c) { return (a - c.cwiseAbs()).minCoeff(); }, 2 * a.x() / 8);
  check_generators(m, box.vertices, "mesh_vertex");
  check_structure(m);
  CHECK(components(m) == 1);
}

TEST_CASE("Voronoi is deterministic, and the same in parallel, sequentially and with either inside test",
          "[voronoi]") {
  const SurfaceMesh mesh = read_mesh(test::corpus_mesh("elephant.off"));  // organic, genus 3
  const MedialComplex first = interior_voronoi(mesh.vertices, mesh);
  REQUIRE(first.num_vertices() > 1000);
  voronoi::InteriorVoronoiOptions sequential;
  sequential.parallel = false;
  voronoi::InteriorVoronoiOptions reference;
  reference.inside = voronoi::InsideMethod::SideOfMesh;
  for (const auto& options : {voronoi::InteriorVoronoiOptions{}, sequential, reference}) {
    const MedialComplex again = interior_voronoi(mesh.vertices, mesh, options);
    CHECK(again.centres == first.centres);
    CHECK(again.radii == first.radii);
    CHECK(again.edges == first.edges);
    CHECK(again.faces == first.faces);
    CHECK(again.generators == first.generators);
    CHECK(again.edge_props.labels.all() == first.edge_props.labels.all());
    CHECK(again.face_props.labels.all() == first.face_props.labels.all());
  }
  check_generators(first, mesh.vertices, "mesh_vertex");
  check_structure(first);
}

TEST_CASE("Voronoi connectivity options: faces, edges only, spheres only", "[voronoi]") {
  const SurfaceMesh capsule = testing::make_capsule(0.5, 1.0, 24);
  voronoi::InteriorVoronoiOptions options;
  voronoi::InteriorVoronoiReport report;
  const MedialComplex full = interior_voronoi(capsule.vertices, capsule, options, &report);
  CHECK(report.voronoi_faces > 0);
  CHECK(full.faces.size() >= report.voronoi_faces);
  CHECK(full.edges.size() > report.voronoi_edges);  // + fan diagonals
  options.connectivity = voronoi::Connectivity::Edges;
  const MedialComplex edges = interior_voronoi(capsule.vertices, capsule, options);
  CHECK(edges.centres == full.centres);
  CHECK(edges.faces.empty());
  CHECK(edges.edges.size() == report.voronoi_edges);
  CHECK(std::equal(edges.edges.begin(), edges.edges.end(), full.edges.begin()));
  options.connectivity = voronoi::Connectivity::None;
  const MedialComplex spheres = interior_voronoi(capsule.vertices, capsule, options);
  CHECK(spheres.centres == full.centres);
  CHECK(spheres.radii == full.radii);
  CHECK(spheres.edges.empty());
  CHECK(spheres.faces.empty());
  CHECK(spheres.generators == full.generators);
}

TEST_CASE("Voronoi of samples: generators index the samples; duplicate points merged", "[voronoi]") {
  const SurfaceMesh sphere = testing::make_sphere(1.0, 2);
  // Samples: the vertices twice over (duplicates) plus the face centres pushed onto the sphere.
  std::vector<Vec3> samples = sphere.vertices;
  samples.insert(samples.end(), sphere.vertices.begin(), sphere.vertices.end());
  for (const Tri& f : sphere.faces)
    samples.push_back(((sphere.vertices[f[0]] + sphere.vertices[f[1]] + sphere.vertices[f[2]]) / 3).normalized());
  voronoi::InteriorVoronoiOptions options;
  options.generator_kind = "sample";
  voronoi::InteriorVoronoiReport report;
  const MedialComplex m = interior_voronoi(samples, sphere, options, &report);
  CHECK(report.points == sphere.vertices.size() + sphere.faces.size());
  REQUIRE(m.num_vertices() > 0);
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    CHECK(m.centres[i].norm() < 1e-9);
    for (Index g : m.generators[i]) CHECK((g < sphere.vertices.size() || g >= 2 * sphere.vertices.size()));
  }
  check_generators(m, samples, "sample");
}

TEST_CASE("Voronoi refuses an open mesh and points that span less than 3D", "[voronoi]") {
  SurfaceMesh open = testing::make_sphere(1.0, 2);
  open.faces.pop_back();
  CHECK_THROWS_AS(interior_voronoi(open.vertices, open), std::invalid_argument);
  voronoi::InteriorVoronoiOptions sequential;
  sequential.parallel = false;
  CHECK_THROWS_AS(interior_voronoi(open.vertices, open, sequential), std::invalid_argument);
  const SurfaceMesh sphere = testing::make_sphere(1.0, 2);
  const std::vector<Vec3> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 3, 0}};
  CHECK_THROWS_AS(interior_voronoi(flat, sphere), std::invalid_argument);
}
