// MSD global optimisation (plugins/msd: optimisation, uncovered_regions, output, medial_json):
// notes §7 items 1, 3, 6, 7 and 10 on analytic shapes with analytic medial meshes, on the
// ellipsoid's VMAS medial mesh, and the reader of the authors' medial JSON.
#include "medial_json.hpp"
#include "optimisation.hpp"
#include "output.hpp"
#include "uncovered_regions.hpp"

#include <medax/io.hpp>
#include <medax/testing/shapes.hpp>

#include "../support/test_paths.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

using namespace medax;
using namespace medax::msd;

namespace {

/// A small triangle of M around the origin (a sphere's medial axis is its centre; M needs a facet).
MedialMesh centre_patch(double size) {
  return MedialMesh({{size, 0, 0}, {-size, size, 0}, {-size, -size, 0}}, {{0, 1, 2}}, {});
}

/// Options for analytic shapes: δ of the chord error (as in test_coverage), small budgets.
OptimisationOptions small_options(std::size_t sites) {
  OptimisationOptions options;
  options.initial_sites = sites;
  options.delta_rule = DeltaRule::Value;
  options.coverage.delta = 3e-3;
  options.first_iterations = 8;
  options.add_every = 6;
  options.max_iterations = 20;
  options.search_sphere_vertices = options.fit.templates.sphere_vertices;  // the chord error of δ's choice
  return options;
}

double distance_to_m(const MedialMesh& m, const Vec3& p) { return m.closest_point(p).distance; }

void check_diagram(const Diagram& d, const MedialMesh& m) {
  for (const Vec3& s : d.sites) CHECK(distance_to_m(m, s) < 1e-9);
  for (const Vec3& v : d.skeleton.vertices) CHECK(distance_to_m(m, v) < 1e-9);
  std::set<Segment> sides;
  for (const Tri& t : d.skeleton.triangles)
    for (int k = 0; k < 3; ++k) sides.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  for (const Segment& e : d.skeleton.edges) CHECK(sides.count({std::min(e[0], e[1]), std::max(e[0], e[1])}) == 0);
  CHECK(d.elements.size() == d.primitives.size());
  CHECK(d.coverage.energy >= -1 - 1e-12);
  CHECK(d.coverage.energy <= 0);
}

}  // namespace

TEST_CASE("msd optimisation: one site in a sphere covers it fully and its primitive reaches R") {
  const TargetMesh sphere(testing::make_sphere(1.0, 4));
  const MedialMesh m = centre_patch(1e-3);
  const OptimisationResult r = optimise(sphere, m, small_options(1));
  CHECK(r.stop_reason == "full coverage");
  REQUIRE(r.best.skeleton.vertices.size() == 1);
  check_diagram(r.best, m);
  CHECK(r.best.coverage.energy == Approx(-1).margin(1e-12));
  const MedialComplex skeleton = skeleton_complex(r.best);
  CHECK(skeleton.radii[0] == Approx(1.0).margin(5e-3));  // mean ρ of the sphere primitive
}

TEST_CASE("msd optimisation: a capsule is one edge primitive between two sites on its axis") {
  const TargetMesh capsule(testing::make_capsule(0.3, 1.0, 64));
  const MedialMesh axis({{0, 0, -1}, {0, 0, 0}, {0, 0, 1}}, {}, {{0, 1}, {1, 2}});
  const OptimisationOptions options = small_options(2);
  const SurfaceCrossing crossing(capsule.mesh());
  EnergyEvaluator evaluator(capsule, axis, crossing, resolve_delta(options, capsule));
  const Diagram d = evaluator.evaluate({}, {{0, 0, -1}, {0, 0, 1}});
  check_diagram(d, axis);
  CHECK(d.skeleton.vertices.size() == 2);
  REQUIRE(d.skeleton.edges.size() == 1);
  CHECK(d.skeleton.triangles.empty());
  CHECK(d.coverage.energy == Approx(-1).margin(1e-12));
  CHECK(d.energy.count == 0);
}

TEST_CASE("msd optimisation: a star-shaped ellipsoid is covered by one vertex primitive at its centre") {
  const TargetMesh ellipsoid(testing::make_ellipsoid(1.0, 0.7, 0.5, 4));
  const MedialMesh m = centre_patch(1e-3);
  const OptimisationOptions options = small_options(1);
  const SurfaceCrossing crossing(ellipsoid.mesh());
  EnergyEvaluator evaluator(ellipsoid, m, crossing, resolve_delta(options, ellipsoid));
  const Diagram d = evaluator.evaluate({}, {Vec3::Zero()});
  REQUIRE(d.primitives.size() == 1);
  CHECK(d.coverage.energy < -0.99);
}

TEST_CASE("msd optimisation on the ellipsoid's VMAS medial mesh: invariants, monotone best, counts, determinism") {
  const TargetMesh target(read_mesh(medax::test::data_dir() / "ellipsoid.off"));
  const MedialMesh m = MedialMesh::from_complex(read_ma(medax::test::data_dir() / "msd_ellipsoid_vmas.ma"));
  OptimisationOptions options;
  options.initial_sites = 3;
  options.first_iterations = 6;
  options.add_every = 4;
  options.max_iterations = 12;
  options.search_sphere_vertices = 100;
  options.fit.templates.sphere_vertices = 200;
  const OptimisationResult r = optimise(target, m, options);
  check_diagram(r.best, m);
  REQUIRE(!r.log.empty());
  for (std::size_t i = 1; i < r.log.size(); ++i) CHECK(r.log[i].best <= r.log[i - 1].best);
  for (const IterationLog& it : r.log)
    if (!it.energy.rejected) CHECK((it.energy.coverage >= -1 && it.energy.coverage <= 0));
  const Counts c = count_elements(r.best);
  std::size_t directions = 0;
  for (const Primitive& p : r.best.primitives) directions += p.fitted ? p.shape.size() : 0;
  CHECK(c.discrete ==
        r.best.skeleton.vertices.size() + r.best.skeleton.edges.size() + r.best.skeleton.triangles.size());
  CHECK(c.continuous == directions + 3 * r.best.skeleton.vertices.size());
  const OptimisationResult again = optimise(target, m, options);
  CHECK(again.best.sites == r.best.sites);
  CHECK(again.best.energy.total == r.best.energy.total);
  CHECK(again.log.size() == r.log.size());
}

TEST_CASE("msd optimisation: E_cent is zero at the cell centroids and grows away from them") {
  const MedialMesh strip({{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}}, {{0, 1, 3}, {0, 3, 2}}, {});
  const std::vector<Vec3> centred{{0.5, 0.5, 0}, {1.5, 0.5, 0}};
  CHECK(centroid_energy(centred, restricted_voronoi(strip, centred)) == Approx(0).margin(1e-12));
  const std::vector<Vec3> shifted{{0.25, 0.5, 0}, {1.5, 0.5, 0}};
  CHECK(centroid_energy(shifted, restricted_voronoi(strip, shifted)) > 1e-3);
}

TEST_CASE("msd uncovered regions: a tetrahedralised box splits into the uncovered slabs, ranked by volume") {
  const SurfaceMesh box = testing::make_box(1.0, 0.5, 0.5, 4);  // [-1,1]×[-0.5,0.5]², volume 2
  const SolidTets tets = tetrahedralize_solid(box, "pq2");
  REQUIRE(tets.size() > 10);
  double volume = 0;
  for (double v : tets.volumes) volume += v;
  CHECK(volume == Approx(2.0).epsilon(1e-9));
  std::vector<char> covered(tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const double x = tets.centroids[t].x();
    covered[t] = x > -0.5 && x < 0.2;  // uncovered: x < -0.5 (about 0.5) and x > 0.2 (about 0.8)
  }
  const auto regions = uncovered_regions(tets, covered);
  REQUIRE(regions.size() == 2);
  CHECK(regions[0].volume > regions[1].volume);
  CHECK(regions[0].centre.x() > 0.2);
  CHECK(regions[1].centre.x() < -0.5);
  CHECK(regions[0].volume == Approx(0.8).epsilon(0.15));
  CHECK(uncovered_regions(tets, std::vector<char>(tets.size(), 1)).empty());
}

TEST_CASE("msd medial JSON: the authors' format is read, exact rationals included") {
  // Coordinates as a number, a rational string, and the authors' character codes of "1/4".
  const std::string text = R"({
    "vertices": [[7, {"pos": [0, "1/2", [49, 47, 52, 0, 0]], "neighboring-edges": [], "neighboring-triangles": [0]}],
                 [3, {"pos": [1, 0, 0]}], [5, {"pos": ["0", "1", "-3/2"]}]],
    "edges": [[0, {"vidx": [3, 7], "neighboring-triangles": [0]}]],
    "triangles": [[0, {"vidx": [7, 3, 5], "eidx": [0, 1, 2]}]],
    "edge-vid-to-edge-id": {"3-7": 0}, "vtx-counter": 8})";
  const MedialComplex m = parse_medial_json(text, "hand.json");
  REQUIRE(m.num_vertices() == 3);
  CHECK(m.centres[0] == Vec3(0, 0.5, 0.25));
  CHECK(m.centres[2] == Vec3(0, 1, -1.5));
  REQUIRE(m.edges.size() == 1);
  CHECK(m.edges[0] == Segment{1, 0});
  REQUIRE(m.faces.size() == 1);
  CHECK(m.faces[0] == Tri{0, 1, 2});
}

TEST_CASE("msd medial JSON: malformed files are refused with file, position and reason") {
  const auto refusal = [](const std::string& text) {
    try {
      parse_medial_json(text, "m.json");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refusal(R"({"vertices": [)"), Catch::Contains("m.json: byte"));
  CHECK_THAT(refusal(R"({"edges": [], "triangles": []})"), Catch::Contains("no \"vertices\" list"));
  const std::string bad_vertex = R"({"vertices": [[1, {"pos": [0, "x/2", 0]}]], "edges": [], "triangles": []})";
  CHECK_THAT(refusal(bad_vertex), Catch::Contains("m.json: vertices[0] (id 1): coordinate \"x/2\" is no number"));
  const std::string bad_edge =
      R"({"vertices": [[1, {"pos": [0, 0, 0]}]], "edges": [[4, {"vidx": [1, 9]}]], "triangles": []})";
  CHECK_THAT(refusal(bad_edge), Catch::Contains("edges[0] (id 4): vertex id 9 is not in \"vertices\""));
  const std::string short_triangle =
      R"({"vertices": [[1, {"pos": [0, 0, 0]}]], "edges": [], "triangles": [[0, {"vidx": [1, 1]}]]})";
  CHECK_THAT(refusal(short_triangle), Catch::Contains("\"vidx\" must list 3 vertex ids"));
}
