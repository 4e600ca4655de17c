// services::check_mesh: agrees with the manifest's independent checker (datasets/meshcheck.jsonl)
// on the offline corpus and the bundled meshes, finds the problems of real broken meshes, and
// each kind of problem on small hand-made meshes.
#include "conditioning_test_support.hpp"

#include <medax/services/mesh_check.hpp>
#include <medax/testing/shapes.hpp>

#include <chrono>
#include <iostream>

using namespace medax;
using medax::services::check_mesh;
using medax::services::MeshProblemKind;
using medax::services::MeshReport;

namespace {

bool has_problem(const MeshReport& r, MeshProblemKind kind) {
  for (const auto& p : r.problems())
    if (p.kind == kind) return true;
  return false;
}

std::size_t count_lines(const std::string& text) {
  return text.empty() ? 0 : static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
}

}  // namespace

TEST_CASE("check_mesh matches meshcheck.jsonl on the Debian corpus and the bundled meshes; every good one "
          "is a valid solid", "[mesh_check]") {
  // The 12 good CGAL meshes and the bundled sphere and torus; the broken cow and thingi10k-68251.
  auto paths = test::debian_corpus(false);
  REQUIRE(paths.size() == 12);
  paths.push_back(test::data_dir() / "sphere.obj");
  paths.push_back(test::data_dir() / "torus.obj");
  const std::size_t good = paths.size();
  paths.push_back(test::corpus_mesh("bad/cow.off"));
  paths.push_back(test::data_dir() / "bad" / "thingi10k-68251.stl");
  // A few genera spelled out, so a wrong manifest cannot hide a wrong count.
  const std::map<std::string, long long> genus = {{"torus.obj", 1}, {"anchor.off", 4}, {"elephant.off", 3},
                                                  {"couplingdown.off", 9}, {"turbine.off", 11}, {"cheese.off", 133},
                                                  {"armadillo.off", 0}};
  std::size_t genus_seen = 0;
  double total = 0;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const auto& path = paths[i];
    const std::string key = test::manifest_key(path);
    INFO(key);
    REQUIRE(test::manifest_checks().count(key) == 1);
    const auto& expected = test::manifest_checks().at(key);
    const SurfaceMesh mesh = read_mesh(path);
    const MeshReport r = check_mesh(mesh);
    total += r.seconds;
    std::cout << key << ": check " << r.seconds << " s (self-intersections " << r.self_intersection_seconds
              << " s)\n";
    CHECK(r.vertices == expected.at("verts").get<std::size_t>());
    CHECK(r.faces == expected.at("faces").get<std::size_t>());
    CHECK(r.unreferenced_vertices == expected.at("unreferenced_verts").get<std::size_t>());
    CHECK(r.duplicate_vertices == expected.at("duplicate_verts").get<std::size_t>());
    CHECK(r.degenerate_faces == expected.at("degenerate_faces").get<std::size_t>());
    CHECK(r.duplicate_faces == expected.at("duplicate_faces").get<std::size_t>());
    CHECK(r.edges == expected.at("edges").get<std::size_t>());
    CHECK(r.boundary_edges == expected.at("boundary_edges").get<std::size_t>());
    CHECK(r.boundary_loops == expected.at("boundary_loops").get<std::size_t>());
    CHECK(r.nonmanifold_edges == expected.at("nonmanifold_edges").get<std::size_t>());
    CHECK(r.nonmanifold_vertices == expected.at("nonmanifold_verts").get<std::size_t>());
    CHECK(r.inconsistent_edges == expected.at("inconsistent_edges").get<std::size_t>());
    CHECK(r.components == expected.at("components").get<std::size_t>());
    CHECK(r.euler_characteristic == expected.at("euler_char").get<long long>());
    // The manifest's "closed" is "watertight": no boundary and no non-manifold edge.
    CHECK((r.closed && r.nonmanifold_edges == 0) == expected.at("closed").get<bool>());
    if (!expected.at("genus").is_null()) {
      REQUIRE(r.genus.has_value());
      CHECK(*r.genus == expected.at("genus").get<long long>());
    }
    if (expected.contains("outward")) CHECK(r.outward == expected.at("outward").get<bool>());
    REQUIRE(r.self_intersecting.has_value());
    CHECK(*r.self_intersecting == expected.at("self_intersecting").get<bool>());
    CHECK(r.intersecting_pairs == expected.at("si_pairs").get<std::size_t>());
    CHECK(r.intersecting_faces == expected.at("si_faces").get<std::size_t>());
    if (!expected.at("cgal_self_intersect").is_null())
      CHECK(*r.self_intersecting == expected.at("cgal_self_intersect").get<bool>());
    if (i < good) {
      CHECK(r.ok());
      CHECK(r.valid_solid());
      CHECK(r.closed);
      CHECK(r.manifold);
      CHECK(r.outward);
      CHECK(r.describe_problems().empty());
      if (genus.count(key)) {
        ++genus_seen;
        CHECK(r.genus == std::optional<long long>(genus.at(key)));
      }
    } else {
      CHECK_FALSE(r.valid_solid());
    }
  }
  CHECK(genus_seen == genus.size());
  std::cout << "all " << paths.size() << " checks: " << total << " s\n";
}

// The counts on the CGAL meshes (pig, elephant-with-holes, degtri_sliding) come from an exact
// count on the files themselves (edges with one face, their connected loops, vertices whose
// decimal coordinates repeat an earlier vertex's, faces whose exact cross product is zero) and
// CGAL's self_intersections on a Surface_mesh (pig: 3 pairs); the others from meshcheck.jsonl.
TEST_CASE("each broken mesh gets the problems the manifest names", "[mesh_check]") {
  {
    const MeshReport r = check_mesh(read_mesh(test::corpus_mesh("bad/pig.off")));
    CHECK_FALSE(r.valid_solid());
    CHECK(has_problem(r, MeshProblemKind::Holes));
    CHECK(r.describe_problems().find("7 boundary loops (holes; 55 boundary edges): run `repair` with "
                                     "fill_holes: true") != std::string::npos);
    CHECK(r.intersecting_pairs == 3);
  }
  {
    const MeshReport r = check_mesh(read_mesh(test::corpus_mesh("bad/elephant-with-holes.off")));
    CHECK_FALSE(r.valid_solid());
    CHECK(has_problem(r, MeshProblemKind::DuplicateVertices));
    CHECK(has_problem(r, MeshProblemKind::Holes));
    CHECK(r.duplicate_vertices == 65);
    CHECK(r.boundary_edges == 1353);
    CHECK(r.describe_problems().find("65 duplicate vertices") != std::string::npos);
  }
  {
    const MeshReport r = check_mesh(read_mesh(test::corpus_mesh("bad/degtri_sliding.off")));
    CHECK_FALSE(r.valid_solid());
    CHECK(has_problem(r, MeshProblemKind::DegenerateFaces));
    CHECK(r.degenerate_faces == 4);
    CHECK(r.describe_problems().find("4 degenerate faces") != std::string::npos);
  }
  const auto dir = test::data_dir() / "bad";
  {
    const MeshReport r = check_mesh(read_mesh(dir / "thingi10k-68251.stl"));
    CHECK_FALSE(r.valid_solid());
    CHECK(has_problem(r, MeshProblemKind::NonManifoldEdges));
    CHECK(has_problem(r, MeshProblemKind::SelfIntersections));
    CHECK(r.describe_problems().find("8 non-manifold edges") != std::string::npos);
    CHECK(r.describe_problems().find("not watertight") != std::string::npos);
  }
  {
    const MeshReport r = check_mesh(read_mesh(test::corpus_mesh("bad/cow.off")));
    CHECK_FALSE(r.valid_solid());
    CHECK(r.closed);
    CHECK(r.manifold);
    CHECK(has_problem(r, MeshProblemKind::SelfIntersections));
    CHECK(r.describe_problems().find("101 self-intersecting triangle pairs") != std::string::npos);
  }
}

TEST_CASE("check_mesh finds each problem kind on small meshes, one line each with its fix", "[mesh_check]") {
  const SurfaceMesh tet = test::tetrahedron();
  SECTION("a closed tetrahedron is valid, genus 0") {
    const MeshReport r = check_mesh(tet);
    CHECK(r.ok());
    CHECK(r.genus == std::optional<long long>(0));
    CHECK(r.euler_characteristic == 2);
    CHECK(r.signed_volume == Approx(1.0 / 6.0));
  }
  SECTION("reversed: inward") {
    const MeshReport r = check_mesh(test::reversed(tet));
    CHECK(has_problem(r, MeshProblemKind::InwardOrientation));
    CHECK_FALSE(r.outward);
    CHECK(r.describe_problems().find("oriented inward") != std::string::npos);
    CHECK(count_lines(r.describe_problems()) == 1);
  }
  SECTION("one face flipped: inconsistent orientation") {
    SurfaceMesh m = tet;
    std::swap(m.faces[3][1], m.faces[3][2]);
    const MeshReport r = check_mesh(m);
    CHECK(r.inconsistent_edges == 3);
    CHECK(has_problem(r, MeshProblemKind::InconsistentOrientation));
  }
  SECTION("one face missing: a hole of 3 edges") {
    SurfaceMesh m = tet;
    m.faces.pop_back();
    const MeshReport r = check_mesh(m);
    CHECK(r.boundary_edges == 3);
    CHECK(r.boundary_loops == 1);
    CHECK_FALSE(r.closed);
    CHECK_FALSE(r.genus.has_value());
    CHECK(r.describe_problems() ==
          "1 boundary loop (holes; 3 boundary edges): run `repair` with fill_holes: true, or close the holes in the mesh");
  }
  SECTION("two tetrahedra on one edge: non-manifold edge") {
    // The second shares vertices 0 and 1 (the edge along x) and lies below z = 0.
    SurfaceMesh m = tet;
    m.vertices.push_back(Vec3(0, -1, -1));
    m.vertices.push_back(Vec3(0.5, -1, -2));
    const Index a = 4, b = 5;
    m.faces.push_back({0, 1, a});
    m.faces.push_back({1, b, a});
    m.faces.push_back({0, a, b});
    m.faces.push_back({0, b, 1});
    const MeshReport r = check_mesh(m);
    CHECK(r.nonmanifold_edges == 1);
    CHECK_FALSE(r.manifold);
    CHECK(has_problem(r, MeshProblemKind::NonManifoldEdges));
  }
  SECTION("two tetrahedra on one vertex: non-manifold vertex, touching") {
    SurfaceMesh m = tet;
    const SurfaceMesh other = test::tetrahedron(Vec3::Zero(), -1.0);  // mirrored through vertex 0
    m.vertices.insert(m.vertices.end(), other.vertices.begin() + 1, other.vertices.end());
    for (Tri f : other.faces) {
      for (Index& v : f) v = v == 0 ? 0 : v + 3;
      m.faces.push_back({f[0], f[2], f[1]});  // the mirror flips orientation: flip back
    }
    const MeshReport r = check_mesh(m);
    CHECK(r.nonmanifold_vertices == 1);
    CHECK(r.nonmanifold_edges == 0);
    CHECK(r.closed);
    CHECK(has_problem(r, MeshProblemKind::NonManifoldVertices));
    CHECK(r.self_intersecting == std::optional<bool>(false));  // they only share the vertex
  }
  SECTION("two overlapping tetrahedra: self-intersecting; disjoint ones are not") {
    const MeshReport overlap = check_mesh(test::merged(tet, test::tetrahedron(Vec3(0.2, 0.2, 0.2))));
    CHECK(overlap.self_intersecting == std::optional<bool>(true));
    CHECK(overlap.intersecting_pairs > 0);
    CHECK(overlap.components == 2);
    CHECK(has_problem(overlap, MeshProblemKind::SelfIntersections));
    const MeshReport apart = check_mesh(test::merged(tet, test::tetrahedron(Vec3(2, 0, 0))));
    CHECK(apart.ok());
    CHECK(apart.components == 2);
    CHECK(apart.genus == std::optional<long long>(0));
    CHECK(apart.genus_per_component == std::vector<long long>{0, 0});
  }
  SECTION("coincident but distinct vertices touch: duplicate vertex and self-intersection") {
    SurfaceMesh m = test::merged(tet, test::tetrahedron(Vec3(1, 0, 0)));  // vertex (1,0,0) twice
    const MeshReport r = check_mesh(m);
    CHECK(r.duplicate_vertices == 1);
    CHECK(r.self_intersecting == std::optional<bool>(true));
  }
  SECTION("degenerate, duplicate faces and unreferenced vertices") {
    SurfaceMesh m = tet;
    m.faces.push_back({0, 0, 1});                   // repeated corner
    m.vertices.push_back(Vec3(0.5, 0, 0));          // on the edge 0-1: a collinear face
    m.faces.push_back({0, 1, 4});
    m.faces.push_back(m.faces[0]);                  // duplicate
    m.vertices.push_back(Vec3(9, 9, 9));            // unreferenced
    const MeshReport r = check_mesh(m);
    CHECK(r.degenerate_faces == 2);
    CHECK(r.duplicate_faces == 1);
    CHECK(r.unreferenced_vertices == 1);
    CHECK(has_problem(r, MeshProblemKind::DegenerateFaces));
    CHECK(has_problem(r, MeshProblemKind::DuplicateFaces));
    CHECK(has_problem(r, MeshProblemKind::UnreferencedVertices));
    for (const auto& p : r.problems()) CHECK(p.message.find('\n') == std::string::npos);
  }
  SECTION("no faces") {
    const MeshReport r = check_mesh(SurfaceMesh{});
    CHECK(has_problem(r, MeshProblemKind::Empty));
    CHECK_FALSE(r.valid_solid());
  }
  SECTION("a face index out of range is an error, not a crash") {
    SurfaceMesh m = tet;
    m.faces.push_back({0, 1, 7});
    CHECK_THROWS_AS(check_mesh(m), std::invalid_argument);
  }
  SECTION("self-intersection test can be skipped") {
    services::MeshCheckOptions o;
    o.self_intersections = false;
    const MeshReport r = check_mesh(test::merged(tet, test::tetrahedron(Vec3(0.2, 0.2, 0.2))), o);
    CHECK_FALSE(r.self_intersecting.has_value());
    CHECK(r.summary().find("not tested") != std::string::npos);
  }
}

TEST_CASE("check_mesh on analytic shapes: genus from the Euler characteristic", "[mesh_check]") {
  CHECK(check_mesh(testing::make_sphere(1.0, 3)).genus == std::optional<long long>(0));
  CHECK(check_mesh(testing::make_torus(2.0, 0.5, 48, 24)).genus == std::optional<long long>(1));
  CHECK(check_mesh(testing::make_box(1, 2, 3, 4)).ok());
  CHECK(check_mesh(testing::make_capsule(0.5, 1.0, 32)).ok());
}

namespace {

SurfaceMesh scaled(SurfaceMesh m, double s) {
  for (Vec3& p : m.vertices) p *= s;
  return m;
}

/// tests/data/cube.off (side 2, centred at 0) with a cube of side 1 inside it, the inner one
/// facing inward (a hollow solid) or outward (a solid inside a solid).
SurfaceMesh cube_in_cube(bool inner_faces_inward) {
  const SurfaceMesh outer = read_mesh(test::data_dir() / "cube.off");
  const SurfaceMesh inner = scaled(outer, 0.5);
  return test::merged(outer, inner_faces_inward ? test::reversed(inner) : inner);
}

constexpr double kScales[] = {1e-120, 1e-6, 1.0, 1e6, 1e120};

}  // namespace

TEST_CASE("check_mesh: an inward-facing closed mesh is named, with the same message at every scale",
          "[mesh_check][orientation]") {
  const SurfaceMesh ellipsoid = read_mesh(test::data_dir() / "ellipsoid.off");
  const std::string expected = check_mesh(test::reversed(ellipsoid)).describe_problems();
  CHECK_THAT(expected, Catch::Contains("faces oriented inward") && Catch::Contains("`repair` flips them outward"));
  for (double s : kScales) {
    INFO("scale " << s);
    const MeshReport inward = check_mesh(scaled(test::reversed(ellipsoid), s));
    CHECK(inward.relative_volume < 0);
    CHECK_FALSE(inward.valid_solid());
    REQUIRE(inward.problems().size() == 1);
    CHECK(inward.problems()[0].kind == MeshProblemKind::InwardOrientation);
    CHECK(inward.describe_problems() == expected);
    // The same mesh facing out is valid at every scale (at 1e±120 the raw volume under- or
    // overflows: the orientation is decided in unit coordinates).
    const MeshReport outward = check_mesh(scaled(ellipsoid, s));
    CHECK(outward.valid_solid());
    CHECK(outward.relative_volume == Approx(-inward.relative_volume));
  }
}

TEST_CASE("check_mesh: a hollow cube is valid, a cube inside a cube facing out is a misoriented shell",
          "[mesh_check][orientation]") {
  for (double s : kScales) {
    INFO("scale " << s);
    const MeshReport hollow = check_mesh(scaled(cube_in_cube(true), s));
    CHECK(hollow.components == 2);
    CHECK(hollow.misoriented_shells == 0);
    CHECK(hollow.valid_solid());
    CHECK(hollow.relative_volume == Approx(1.0 - 0.125));  // unit outer cube minus the cavity

    const MeshReport nested = check_mesh(scaled(cube_in_cube(false), s));
    CHECK(nested.misoriented_shells == 1);
    CHECK_FALSE(nested.valid_solid());
    REQUIRE(nested.problems().size() == 1);
    CHECK(nested.problems()[0].kind == MeshProblemKind::MisorientedShells);
    CHECK(nested.problems()[0].automatic);
    CHECK(nested.describe_problems() == check_mesh(cube_in_cube(false)).describe_problems());
    CHECK_THAT(nested.summary(), Catch::Contains("1 misoriented shell"));
  }
  // Side by side, both facing out: two solids, nothing nested.
  const SurfaceMesh cube = read_mesh(test::data_dir() / "cube.off");
  SurfaceMesh apart = cube;
  for (Vec3& p : apart.vertices) p.x() += 3.0;
  const MeshReport two = check_mesh(test::merged(cube, apart));
  CHECK(two.misoriented_shells == 0);
  CHECK(two.valid_solid());
}
