// MSD skeleton construction (plugins/msd: medial_mesh, construction): notes §7 items 1–3, 10 on
// analytic medial meshes (a slab's sheet, a capsule's axis, a torus's core circle) and on VMAS
// medial mesh of a real shape (tests/data/msd_ellipsoid_vmas.ma: `medax run pipelines/vmas.yaml
// --input tests/data/ellipsoid.off`, 23 vertices).
#include "construction.hpp"

#include <medax/io.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>

#include "../support/test_paths.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>

using namespace medax;
using namespace medax::msd;

namespace {

/// A polyline of `n` dangling edges from a to b.
MedialMesh polyline_mesh(const Vec3& a, const Vec3& b, int n) {
  std::vector<Vec3> points;
  std::vector<Segment> edges;
  for (int k = 0; k <= n; ++k) points.push_back(a + (b - a) * (static_cast<double>(k) / n));
  for (Index k = 0; k < static_cast<Index>(n); ++k) edges.push_back({k, k + 1});
  return MedialMesh(points, {}, edges);
}

/// The square [-h, h]² at z = 0 as an n × n grid of split quads.
MedialMesh square_sheet(double h, int n) {
  std::vector<Vec3> points;
  std::vector<Tri> triangles;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) points.push_back({-h + 2 * h * i / n, -h + 2 * h * j / n, 0});
  auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return MedialMesh(points, triangles, {});
}

/// The core circle of radius R in the plane z = 0, as n dangling edges.
MedialMesh circle_mesh(double R, int n) {
  std::vector<Vec3> points;
  std::vector<Segment> edges;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    points.push_back({R * std::cos(a), R * std::sin(a), 0});
    edges.push_back({static_cast<Index>(k), static_cast<Index>((k + 1) % n)});
  }
  return MedialMesh(points, {}, edges);
}

/// Notes §7 items 1–3 for any skeleton of `mesh` inside `surface`.
void check_invariants(const Skeleton& s, const MedialMesh& mesh, const SurfaceMesh& surface,
                      const SurfaceCrossing& crossing, std::size_t num_sites) {
  REQUIRE(s.vertices.size() >= num_sites);
  for (std::size_t v = 0; v < s.vertices.size(); ++v) {
    CHECK(static_cast<bool>(s.is_site[v]) == (v < num_sites));
    CHECK(mesh.closest_point(s.vertices[v]).distance < 1e-9);                                 // on M
    CHECK(services::winding_number(surface, s.vertices[v]) > 0.5);                          // inside S
  }
  std::set<Segment> sides;
  for (const auto& t : s.triangles) {
    CHECK((t[0] < t[1] && t[1] < t[2]));  // sorted, so no repeated vertex
    CHECK((s.vertices[t[1]] - s.vertices[t[0]]).cross(s.vertices[t[2]] - s.vertices[t[0]]).norm() > 0);
    CHECK_FALSE(crossing.crosses(s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]]));
    sides.insert({t[0], t[1]}), sides.insert({t[1], t[2]}), sides.insert({t[0], t[2]});
  }
  CHECK(std::set<Tri>(s.triangles.begin(), s.triangles.end()).size() == s.triangles.size());
  CHECK(std::set<Segment>(s.edges.begin(), s.edges.end()).size() == s.edges.size());
  for (const auto& e : s.edges) {
    CHECK(e[0] < e[1]);
    CHECK_FALSE(sides.count(e));  // Ê shares no side with F̂
    CHECK_FALSE(crossing.crosses(s.vertices[e[0]], s.vertices[e[1]]));
  }
  CHECK(s.stats.unresolved_edges == 0);
  CHECK(s.stats.crossing_triangles == 0);
  CHECK(services::complex_topology(s.vertices.size(), s.edges, s.triangles).components() == 1);
}

std::vector<Vec3> vertex_positions(const MedialMesh& mesh, const std::vector<Index>& ids) {
  std::vector<Vec3> out;
  for (Index v : ids) out.push_back(mesh.points()[v]);
  return out;
}

}  // namespace

TEST_CASE("farthest-point sites on a path graph are the maximal-distance picks") {
  const auto path = polyline_mesh({0, 0, 0}, {9, 0, 0}, 9);
  CHECK(path.distance(0, 9) == Approx(9));
  CHECK(path.shortest_path(2, 5) == std::vector<Index>{2, 3, 4, 5});
  const auto sites = farthest_point_sites(path, 4, 0);
  // 0, then the far end 9, then the middle (4 and 5 tie at distance 4: the lower index), then
  // a vertex at distance 2 from {0, 4, 9} (2 is the lowest such).
  CHECK(sites == std::vector<Index>{0, 9, 4, 2});
  for (std::size_t k = 1; k < sites.size(); ++k) {
    auto nearest = [&](Index v) {
      double d = 1e300;
      for (std::size_t j = 0; j < k; ++j) d = std::min(d, path.distance(sites[j], v));
      return d;
    };
    for (Index v = 0; v < path.points().size(); ++v) CHECK(nearest(sites[k]) >= nearest(v));
  }
  CHECK(farthest_point_sites(path, 20, 3).size() == 10);
  CHECK_THROWS_AS(farthest_point_sites(path, 2, 10), std::invalid_argument);
}

TEST_CASE("medial mesh from a complex: duplicates merged, the largest component kept") {
  MedialComplex mc;
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(1, 1, 0),  //
                        Vec3(5, 5, 5), Vec3(6, 5, 5)})
    mc.add_vertex(p, 0.1);
  mc.add_face(0, 1, 2);
  mc.add_face(3, 4, 2);  // vertex 3 duplicates vertex 1: the triangles share an edge
  mc.add_edge(5, 6);     // a second, smaller component
  mc.add_edge(0, 1);     // a triangle side, not a dangling edge
  const auto mesh = MedialMesh::from_complex(mc);
  CHECK(mesh.points().size() == 4);
  CHECK(mesh.triangles().size() == 2);
  CHECK(mesh.dangling_edges().empty());
  CHECK(mesh.edges().size() == 5);
  const auto shared = mesh.edge_index(1, 2);
  REQUIRE(shared);
  CHECK(mesh.edge_facets(*shared).size() == 2);
  CHECK(mesh.facet_neighbours(0) == std::vector<Index>{1});
  const auto hit = mesh.closest_point({0.2, 0.2, 3});
  CHECK(hit.distance == Approx(3));
  CHECK(hit.facet == 0);
}

TEST_CASE("a slab's planar medial sheet with 3 sites gives one triangle") {
  const auto surface = testing::make_box(0.5, 0.5, 0.05, 4);
  const SurfaceCrossing crossing(surface);
  const auto sheet = square_sheet(0.45, 8);
  const std::vector<Vec3> sites{{-0.3, -0.3, 0}, {0.3, -0.25, 0}, {0.02, 0.3, 0}};
  const auto s = construct_skeleton(sheet, sites, crossing);
  check_invariants(s, sheet, surface, crossing, 3);
  CHECK(s.vertices.size() == 3);
  CHECK(s.triangles == std::vector<Tri>{{0, 1, 2}});
  CHECK(s.edges.empty());
  // The cells partition the sheet, and each piece belongs to its nearest site.
  double area = 0;
  for (const auto& piece : s.pieces) {
    area += piece.measure;
    for (std::size_t j = 0; j < sites.size(); ++j)
      CHECK((piece.centroid - sites[piece.site]).norm() <= (piece.centroid - sites[j]).norm() + 1e-12);
  }
  CHECK(area == Approx(0.9 * 0.9).epsilon(1e-12));
  const auto cells = restricted_voronoi(sheet, sites);
  REQUIRE(cells.size() == s.pieces.size());
  for (std::size_t p = 0; p < cells.size(); ++p) CHECK(cells[p].polygon == s.pieces[p].polygon);
  // Each cell is the square cut by a convex Voronoi region: its centroid lies in its own region.
  const auto centroids = cell_centroids(cells, sites.size());
  for (std::size_t c = 0; c < sites.size(); ++c)
    for (std::size_t j = 0; j < sites.size(); ++j) CHECK((centroids[c] - sites[c]).norm() <= (centroids[c] - sites[j]).norm());
  // Two sites split the sheet at y = 0.1: the upper cell is the band 0.1 <= y <= 0.45.
  const auto bands = cell_centroids(restricted_voronoi(sheet, {{0, -0.1, 0}, {0, 0.3, 0}}), 2);
  CHECK(bands[1].y() == Approx((0.1 + 0.45) / 2));
  CHECK(bands[1].x() == Approx(0).margin(1e-12));
}

TEST_CASE("4 cocircular sites meet at one point of the sheet: a polygon, fan-triangulated") {
  const auto surface = testing::make_box(0.5, 0.5, 0.05, 4);
  const SurfaceCrossing crossing(surface);
  const auto sheet = square_sheet(0.45, 8);  // a grid vertex at the origin, on both bisectors
  const std::vector<Vec3> sites{{-0.2, -0.2, 0}, {0.2, -0.2, 0}, {0.2, 0.2, 0}, {-0.2, 0.2, 0}};
  const auto s = construct_skeleton(sheet, sites, crossing);
  check_invariants(s, sheet, surface, crossing, 4);
  CHECK(s.stats.polygons == 1);
  REQUIRE(s.triangles.size() == 2);
  double area = 0;
  for (const auto& t : s.triangles) area += 0.5 * (s.vertices[t[1]] - s.vertices[t[0]]).cross(s.vertices[t[2]] - s.vertices[t[0]]).norm();
  CHECK(area == Approx(0.4 * 0.4));  // the two triangles tile the square of the sites
  CHECK(s.edges.empty());
}

TEST_CASE("a closed tetrahedron in the RDT is thinned by its smallest face") {
  // M a closed sphere (a test complex, not a medial axis), S a larger sphere around it: the 4
  // cells of 4 sites meet pairwise and by threes, so the RDT is the closed tetrahedron.
  const auto surface = testing::make_sphere(2.0, 2);
  const SurfaceCrossing crossing(surface);
  const auto ball = testing::make_sphere(1.0, 3);
  const MedialMesh shell(ball.vertices, ball.faces, {});
  const std::vector<Vec3> sites{Vec3(1, 1, 1).normalized(), Vec3(1, -1, -1).normalized(), Vec3(-1, 1, -0.6).normalized(),
                                Vec3(-1, -1, 1.3).normalized()};
  const auto s = construct_skeleton(shell, sites, crossing);
  check_invariants(s, shell, surface, crossing, 4);
  CHECK(s.stats.tetrahedra_thinned == 1);
  REQUIRE(s.triangles.size() == 3);
  // The missing face is the smallest of the four.
  auto area = [&](Index a, Index b, Index c) { return (s.vertices[b] - s.vertices[a]).cross(s.vertices[c] - s.vertices[a]).norm(); };
  std::set<Tri> all{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& t : s.triangles) all.erase(t);
  REQUIRE(all.size() == 1);
  const Tri gone = *all.begin();
  for (const auto& t : s.triangles) CHECK(area(gone[0], gone[1], gone[2]) < area(t[0], t[1], t[2]));
  CHECK(services::complex_topology(s.vertices.size(), s.edges, s.triangles).b2 == 0);
}

TEST_CASE("an orphan component of a cell goes to its neighbour: a hairpin keeps a path skeleton") {
  // Lower arm y = -0.15, bend x = 0.5, upper arm y = 0.15. Site 0's Voronoi cell also holds the
  // upper arm's end (x < -0.34), which touches M only through site 2's part: an orphan.
  std::vector<Vec3> corners{{-0.5, -0.15, 0}, {0.5, -0.15, 0}, {0.5, 0.15, 0}, {-0.5, 0.15, 0}};
  std::vector<Vec3> points;
  std::vector<Segment> edges;
  for (std::size_t c = 0; c + 1 < corners.size(); ++c)
    for (int k = 0; k < 10; ++k) points.push_back(corners[c] + (corners[c + 1] - corners[c]) * (k / 10.0));
  points.push_back(corners.back());
  for (Index k = 0; k + 1 < points.size(); ++k) edges.push_back({k, k + 1});
  const MedialMesh hairpin(points, {}, edges);
  const auto surface = testing::make_box(0.6, 0.25, 0.1, 2);
  const SurfaceCrossing crossing(surface);
  const auto s = construct_skeleton(hairpin, {{-0.5, -0.15, 0}, {0.5, 0, 0}, {0, 0.15, 0}}, crossing);
  check_invariants(s, hairpin, surface, crossing, 3);
  CHECK(s.stats.orphan_components >= 1);
  CHECK(s.edges == std::vector<Segment>{{0, 1}, {1, 2}});  // no edge 0-2 through the orphan
  bool relabelled_upper_end = false;
  for (const auto& piece : s.pieces)
    if (piece.site == 0 && piece.centroid.y() > 0) relabelled_upper_end = piece.cell == 2;
  CHECK(relabelled_upper_end);
}

TEST_CASE("a capsule's axis with 2 sites gives one edge, with 3 a chain") {
  const auto surface = testing::make_capsule(0.2, 1.0, 24);
  const SurfaceCrossing crossing(surface);
  const auto axis = polyline_mesh({0, 0, -1}, {0, 0, 1}, 10);
  const auto two = construct_skeleton(axis, {{0, 0, -0.8}, {0, 0, 0.75}}, crossing);
  check_invariants(two, axis, surface, crossing, 2);
  CHECK(two.edges == std::vector<Segment>{{0, 1}});
  CHECK(two.triangles.empty());
  const auto three = construct_skeleton(axis, {{0, 0, -0.8}, {0, 0, 0.75}, {0, 0, 0.1}}, crossing);
  check_invariants(three, axis, surface, crossing, 3);
  CHECK(three.edges == std::vector<Segment>{{0, 2}, {1, 2}});
}

TEST_CASE("a torus's core circle with 2 sites: the second interface closes the loop inside S") {
  const auto surface = testing::make_torus(1.0, 0.3, 48, 24);
  const SurfaceCrossing crossing(surface);
  const auto circle = circle_mesh(1.0, 32);
  const std::vector<Vec3> sites{{std::cos(0.05), std::sin(0.05), 0}, {std::cos(2.54), std::sin(2.54), 0}};
  const auto s = construct_skeleton(circle, sites, crossing);
  check_invariants(s, circle, surface, crossing, 2);
  CHECK(s.stats.extra_interfaces == 1);
  CHECK(s.stats.bisections >= 1);  // the straight edge through the hole crossed S
  const auto topology = services::complex_topology(s.vertices.size(), s.edges, s.triangles);
  CHECK(topology.b1 == 1);  // one loop, as the torus
  SECTION("without step d the skeleton is a path, not a loop") {
    ConstructionOptions options;
    options.multi_interface = false;
    const auto path = construct_skeleton(circle, sites, crossing, options);
    CHECK(services::complex_topology(path.vertices.size(), path.edges, path.triangles).b1 == 0);
  }
}

TEST_CASE("construction on the VMAS medial mesh of a real shape keeps every invariant") {
  // (joint.off's VMAS mesh has 7 vertices whose triangles leave S, so "inside S" cannot hold.)
  const std::string name = "ellipsoid";
  const auto surface = read_mesh(medax::test::data_dir() / (name + ".off"));
  const auto mesh = MedialMesh::from_complex(read_ma(medax::test::data_dir() / ("msd_" + name + "_vmas.ma")));
  const SurfaceCrossing crossing(surface);
  for (std::size_t k : {1, 3, 5}) {
    CAPTURE(name, k);
    const auto sites = vertex_positions(mesh, farthest_point_sites(mesh, k));
    const auto s = construct_skeleton(mesh, sites, crossing);
    check_invariants(s, mesh, surface, crossing, sites.size());
    const auto again = construct_skeleton(mesh, sites, crossing);
    CHECK(again.vertices == s.vertices);  // deterministic
    CHECK(again.edges == s.edges);
    CHECK(again.triangles == s.triangles);
  }
}

TEST_CASE("construction refuses coincident sites and an empty site list") {
  const auto surface = testing::make_box(0.5, 0.5, 0.05, 2);
  const SurfaceCrossing crossing(surface);
  const auto sheet = square_sheet(0.45, 2);
  CHECK_THROWS_AS(construct_skeleton(sheet, {}, crossing), std::invalid_argument);
  CHECK_THROWS_AS(construct_skeleton(sheet, {{0, 0, 0}, {0, 0, 0}}, crossing), std::invalid_argument);
}
