// services::repair_mesh: cheap fixes always, holes and self-intersections when asked, and a
// re-check of every result: a repair either gives a valid solid of the same shape or says why not.
#include "conditioning_test_support.hpp"

#include <medax/services/mesh_check.hpp>
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>

#include <chrono>
#include <iostream>
#include <map>

using namespace medax;
using medax::services::check_mesh;
using medax::services::repair_mesh;
using medax::services::RepairOptions;
using medax::services::RepairResult;

namespace {

double volume(const SurfaceMesh& m) {
  double v = 0;
  for (const Tri& f : m.faces) v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

RepairOptions everything() {
  RepairOptions o;
  o.fill_holes = true;
  o.remove_self_intersections = true;
  return o;
}

}  // namespace

TEST_CASE("repair leaves a valid mesh untouched", "[mesh_repair]") {
  for (const auto& path : {test::data_dir() / "cube.off", test::data_dir() / "torus.obj",
                           test::corpus_mesh("anchor.off"), test::corpus_mesh("knot.off")}) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    const RepairResult r = repair_mesh(mesh, everything());
    CHECK(r.ok());
    CHECK_FALSE(r.changed);
    CHECK(r.actions.empty());
    CHECK(r.mesh.vertices == mesh.vertices);
    CHECK(r.mesh.faces == mesh.faces);
  }
}

TEST_CASE("repair flips a reversed mesh back outward", "[mesh_repair]") {
  for (const auto& path : {test::data_dir() / "sphere.obj", test::data_dir() / "torus.obj",
                           test::corpus_mesh("fandisk.off")}) {
    INFO(path.filename().string());
    const SurfaceMesh mesh = read_mesh(path);
    const SurfaceMesh inward = test::reversed(mesh);
    REQUIRE_FALSE(check_mesh(inward).valid_solid());
    const RepairResult r = repair_mesh(inward);
    REQUIRE(r.ok());
    CHECK(r.after.outward);
    CHECK(r.mesh.vertices == mesh.vertices);  // nothing to merge or drop: vertices keep their order
    REQUIRE(r.mesh.faces.size() == mesh.faces.size());
    std::size_t same = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) same += test::same_oriented_face(r.mesh.faces[f], mesh.faces[f]);
    CHECK(same == mesh.faces.size());
    CHECK(volume(r.mesh) == Approx(volume(mesh)).epsilon(1e-12));
  }
}

TEST_CASE("repair orients a mesh with mixed face orientations and a nested cavity", "[mesh_repair]") {
  // A sphere with a spherical cavity: the outer shell must face out, the inner one in.
  SurfaceMesh outer = testing::make_sphere(1.0, 2), inner = testing::make_sphere(0.5, 2);
  SurfaceMesh m = test::merged(outer, inner);  // both outward: the cavity faces the wrong way
  for (std::size_t f = 0; f < m.faces.size(); f += 3) std::swap(m.faces[f][1], m.faces[f][2]);  // and mixed
  REQUIRE(check_mesh(m).inconsistent_edges > 0);
  const RepairResult r = repair_mesh(m);
  REQUIRE(r.ok());
  const double expected = 4.0 / 3.0 * M_PI * (1.0 - 0.125);
  CHECK(volume(r.mesh) == Approx(expected).epsilon(0.05));  // the cavity is subtracted
  CHECK(r.after.components == 2);
}

TEST_CASE("repair merges duplicate vertices and removes degenerate faces", "[mesh_repair]") {
  SECTION("a polygon soup with every vertex repeated") {
    const SurfaceMesh cube = read_mesh(test::data_dir() / "cube.off");
    const SurfaceMesh soup = test::exploded(cube);
    const auto before = check_mesh(soup);
    CHECK(before.duplicate_vertices == 36 - 8);
    CHECK(before.boundary_edges == 36);
    const RepairResult r = repair_mesh(soup);
    REQUIRE(r.ok());
    CHECK(r.after.ok());
    CHECK(r.mesh.vertices.size() == 8);
    CHECK(r.mesh.faces.size() == 12);
    CHECK(volume(r.mesh) == Approx(8.0));
  }
  SECTION("a zero-area sliver inside a closed mesh is collapsed, keeping the mesh closed") {
    // Split the cube's edge (a, b) at its midpoint m on one side only, and close the crack with
    // the collinear face (m, a, b).
    SurfaceMesh cube = read_mesh(test::data_dir() / "cube.off");
    const Tri f = cube.faces[0];
    const Index a = f[0], b = f[1], c = f[2];
    const auto m = static_cast<Index>(cube.vertices.size());
    cube.vertices.push_back(0.5 * (cube.vertices[a] + cube.vertices[b]));
    cube.faces[0] = {a, m, c};
    cube.faces.push_back({m, b, c});
    cube.faces.push_back({m, a, b});
    const auto before = check_mesh(cube);
    REQUIRE(before.closed);
    REQUIRE(before.degenerate_faces == 1);
    const RepairResult r = repair_mesh(cube);
    REQUIRE(r.ok());
    CHECK(r.after.degenerate_faces == 0);
    CHECK(volume(r.mesh) == Approx(8.0));
  }
}

TEST_CASE("repair fills holes only when asked", "[mesh_repair]") {
  const SurfaceMesh sphere = read_mesh(test::data_dir() / "sphere.obj");
  // Two holes: the faces around two far-apart vertices (which become unreferenced).
  SurfaceMesh open = sphere;
  const Index v1 = 10, v2 = static_cast<Index>(sphere.vertices.size() - 1);
  REQUIRE((sphere.vertices[v1] - sphere.vertices[v2]).norm() > 0.5);
  open.faces.erase(std::remove_if(open.faces.begin(), open.faces.end(),
                                  [&](const Tri& f) {
                                    return std::find(f.begin(), f.end(), v1) != f.end() ||
                                           std::find(f.begin(), f.end(), v2) != f.end();
                                  }),
                   open.faces.end());
  const auto holes = check_mesh(open);
  REQUIRE(holes.boundary_loops == 2);
  REQUIRE(holes.unreferenced_vertices == 2);

  const RepairResult refused = repair_mesh(open);
  CHECK_FALSE(refused.ok());
  CHECK(refused.after.boundary_loops == holes.boundary_loops);

  RepairOptions fill;
  fill.fill_holes = true;
  const RepairResult filled = repair_mesh(open, fill);
  REQUIRE(filled.ok());
  CHECK(filled.after.genus == std::optional<long long>(0));
  CHECK(services::surface_area(filled.mesh) == Approx(services::surface_area(sphere)).epsilon(0.01));

  RepairOptions small = fill;
  small.max_hole_edges = 3;
  const RepairResult limited = repair_mesh(open, small);
  CHECK_FALSE(limited.ok());
  REQUIRE_FALSE(limited.failures.empty());
  CHECK(limited.failures.front().find("max_hole_edges") != std::string::npos);
}

TEST_CASE("repair removes the self-intersections of two overlapping spheres: their union", "[mesh_repair]") {
  const SurfaceMesh a = testing::make_sphere(1.0, 3);
  SurfaceMesh b = a;
  for (Vec3& v : b.vertices) v.x() += 1.5;
  const SurfaceMesh both = test::merged(a, b);
  REQUIRE(check_mesh(both).self_intersecting == std::optional<bool>(true));
  CHECK_FALSE(repair_mesh(both).ok());  // not asked: refused
  RepairOptions o;
  o.remove_self_intersections = true;
  const RepairResult r = repair_mesh(both, o);
  INFO(r.after.summary());
  REQUIRE(r.ok());
  CHECK(r.after.components == 1);
  // Union of two unit balls at distance d = 1.5: 2·(4/3)π − lens, lens = (π/12)(4 + d)(2 − d)².
  const double single = volume(a);
  const double lens_fraction = (M_PI / 12.0 * 5.5 * 0.25) / (4.0 / 3.0 * M_PI);
  CHECK(volume(r.mesh) == Approx(single * (2.0 - lens_fraction)).epsilon(0.02));
}

TEST_CASE("repair of every broken mesh: a valid solid of the same shape, or the reasons", "[mesh_repair]") {
  std::map<std::string, RepairResult> results;
  auto broken = test::debian_corpus(true);
  broken.push_back(test::data_dir() / "bad" / "thingi10k-68251.stl");
  REQUIRE(broken.size() == 5);
  for (const auto& path : broken) {
    const std::string name = path.filename().string();
    INFO(name);
    const SurfaceMesh mesh = read_mesh(path);
    const auto t0 = std::chrono::steady_clock::now();
    const RepairResult r = repair_mesh(mesh, everything());
    std::cout << name << ": repair " << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
              << " s, " << (r.ok() ? "repaired" : "refused") << "\n";
    // Whatever happened, the report describes the returned mesh.
    const auto recheck = check_mesh(r.mesh);
    CHECK(recheck.valid_solid() == r.ok());
    CHECK(recheck.intersecting_pairs == r.after.intersecting_pairs);
    CHECK(recheck.boundary_edges == r.after.boundary_edges);
    if (r.ok()) {
      CHECK(test::bbox_diag(r.mesh) == Approx(test::bbox_diag(mesh)).epsilon(0.02));
      CHECK(r.after.components <= r.before.components);
    } else {
      CHECK_FALSE(r.after.describe_problems().empty());
      CHECK_FALSE(r.failures.empty());
    }
    results.emplace(name, r);
  }
  // What the CGAL 5.5 repairs give on these files (documented in docs/plugins/conditioning.md).
  const RepairResult& pig = results.at("pig.off");
  CHECK(pig.ok());
  CHECK(pig.after.genus == std::optional<long long>(0));
  CHECK_FALSE(results.at("thingi10k-68251.stl").ok());
  const RepairResult& cow = results.at("cow.off");
  CHECK_FALSE(cow.ok());
  bool rejected = false;
  for (const auto& f : cow.failures) rejected |= f.find("split the surface") != std::string::npos;
  CHECK(rejected);  // CGAL's results would detach the tail: rejected, not returned
}

namespace {

SurfaceMesh times(SurfaceMesh m, double s) {
  for (Vec3& p : m.vertices) p *= s;
  return m;
}

/// The verdict and the log lines of a repair, which must not depend on the coordinates' scale.
std::string verdict(const RepairResult& r) {
  std::string text = r.ok() ? "ok" : "refused";
  for (const std::string& a : r.actions) text += "\n" + a;
  for (const std::string& f : r.failures) text += "\n" + f;
  return text + "\n" + r.before.describe_problems() + "\n" + r.after.describe_problems();
}

}  // namespace

TEST_CASE("repair_mesh flips an inward-facing ellipsoid and nests a cube in a cube as a cavity, at every scale",
          "[mesh_repair][orientation]") {
  const SurfaceMesh inward = test::reversed(read_mesh(test::data_dir() / "ellipsoid.off"));
  const SurfaceMesh cube = read_mesh(test::data_dir() / "cube.off");
  const SurfaceMesh nested = test::merged(cube, times(cube, 0.5));  // both facing out
  const std::string inward_verdict = verdict(repair_mesh(inward));
  const std::string nested_verdict = verdict(repair_mesh(nested));
  for (double s : {1e-120, 1e-6, 1.0, 1e6, 1e120}) {
    INFO("scale " << s);
    const RepairResult flipped = repair_mesh(times(inward, s));
    REQUIRE(flipped.ok());
    CHECK(flipped.after.relative_volume == Approx(-flipped.before.relative_volume));
    CHECK(verdict(flipped) == inward_verdict);

    const RepairResult hollowed = repair_mesh(times(nested, s));
    REQUIRE(hollowed.ok());
    CHECK(hollowed.before.misoriented_shells == 1);
    CHECK(hollowed.after.misoriented_shells == 0);
    // The inner cube (1/8 of the outer one's volume) became a cavity: 1 − 1/8, not 1 + 1/8.
    CHECK(hollowed.before.relative_volume == Approx(1.125));
    CHECK(hollowed.after.relative_volume == Approx(0.875));
    CHECK(verdict(hollowed) == nested_verdict);
  }
}
