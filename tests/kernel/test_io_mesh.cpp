// Surface mesh I/O: OFF, OBJ, PLY and STL written and read back; errors name the file.
#include "kernel_test_support.hpp"

#include <medax/io.hpp>
#include <medax/testing/shapes.hpp>

using namespace medax;
using medax::test::data_file;
using medax::test::scratch_dir;
using medax::test::write_text;

TEST_CASE("the bundled meshes read with their vertex and face counts", "[io][mesh]") {
  const SurfaceMesh cube = read_mesh(data_file("cube.off"));
  CHECK(cube.vertices.size() == 8);
  CHECK(cube.faces.size() == 12);
  const SurfaceMesh ellipsoid = read_mesh(data_file("ellipsoid.off"));
  CHECK(ellipsoid.vertices.size() == 162);
  CHECK(ellipsoid.faces.size() == 320);
  const SurfaceMesh sphere = read_mesh(data_file("sphere.obj"));
  CHECK_FALSE(sphere.faces.empty());
  Index largest = 0;
  for (const Tri& f : sphere.faces) largest = std::max({largest, f[0], f[1], f[2]});
  CHECK(largest + 1 == sphere.vertices.size());
}

TEST_CASE("write_mesh then read_mesh gives the same mesh in every format", "[io][mesh]") {
  const SurfaceMesh mesh = medax::testing::make_ellipsoid(1.5, 1.0 / 3.0, 0.7, 1);
  const auto dir = scratch_dir("io_mesh_round_trip");
  for (const std::string ext : {"off", "obj", "ply", "stl"}) {
    INFO(ext);
    const auto file = dir / ("mesh." + ext);
    write_mesh(file, mesh);
    const SurfaceMesh read = read_mesh(file);
    REQUIRE(read.faces.size() == mesh.faces.size());
    REQUIRE(read.vertices.size() == mesh.vertices.size());
    // Compare geometry face by face (a format may renumber vertices).
    double worst = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, (read.vertices[read.faces[f][k]] - mesh.vertices[mesh.faces[f][k]]).norm());
    CHECK(worst < (ext == "stl" ? 1e-6 : 1e-15));  // STL stores floats
  }
}

TEST_CASE("polygons are fan-triangulated when read", "[io][mesh]") {
  const auto file = write_text(scratch_dir("io_mesh_quad") / "quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const SurfaceMesh mesh = read_mesh(file);
  CHECK(mesh.faces == std::vector<Tri>{{0, 1, 2}, {0, 2, 3}});
}

TEST_CASE("mesh I/O errors name the file", "[io][mesh]") {
  const auto dir = scratch_dir("io_mesh_errors");
  CHECK_THROWS_WITH(read_mesh(dir / "missing.off"), Catch::Contains("missing.off: no such file"));
  write_text(dir / "shape.vtk", "not a mesh");
  CHECK_THROWS_WITH(read_mesh(dir / "shape.vtk"), Catch::Contains("shape.vtk: unsupported mesh format '.vtk'"));
  CHECK_THROWS_AS(write_mesh(dir / "out.vtk", medax::testing::make_sphere(1, 0)), IoError);
  CHECK_FALSE(std::filesystem::exists(dir / "out.vtk"));
  write_text(dir / "garbage.off", "OFF\n3 1 0\n0 0 0\n1 0\n");
  CHECK_THROWS_WITH(read_mesh(dir / "garbage.off"), Catch::Contains("garbage.off"));
  write_text(dir / "bad_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  CHECK_THROWS_WITH(read_mesh(dir / "bad_index.off"), Catch::Contains("bad_index.off"));
}

namespace {

/// The message read_mesh throws for `file`; fails the test when it reads the file.
std::string mesh_error(const std::string& file) {
  try {
    read_mesh(file);
  } catch (const IoError& e) {
    return e.what();
  }
  FAIL("read_mesh accepted " << file);
  return {};
}

}  // namespace

TEST_CASE("hostile meshes are refused with the file, the reason and the line or element", "[io][mesh][bad]") {
  struct Case {
    const char* file;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases = {
      {"empty.off", {"empty.off: empty file"}},
      {"truncated.off", {"truncated.off: the header announces 4 vertices but the file ends after 3 (line 5)", "truncated"}},
      {"truncated.ply", {"truncated.ply: the header announces 4 'vertex' elements", "only 18 bytes"}},
      {"nan.off", {"nan.off: line 4: vertex 1 has the non-finite coordinate 'nan'"}},
      {"inf.obj", {"inf.obj: line 2: vertex 1 has the non-finite coordinate 'inf'"}},
      {"nan.stl", {"nan.stl: line 5: vertex 1 has the non-finite coordinate 'nan'"}},
      {"bad_index.off", {"bad_index.off: line 6: face 0 refers to vertex 7 but the vertices are 0..2"}},
      {"bad_index.obj", {"bad_index.obj: line 4: face 0 refers to vertex 9 but the vertices are 1..3"}},
      {"negative_index.ply", {"negative_index.ply: face 0 refers to vertex -1 but the vertices are 0..2"}},
      {"huge_face.off", {"huge_face.off: line 6: face 0 announces 999999999 corners but lists only 3"}},
      {"points_only.obj", {"points_only.obj: 3 vertices and no faces"}},
      {"points_only.ply", {"points_only.ply: 3 vertices and no faces"}},
  };
  for (const Case& c : cases) {
    INFO(c.file);
    const std::string message = mesh_error(data_file(std::string("bad/") + c.file));
    for (const std::string& part : c.says) CHECK_THAT(message, Catch::Contains(part));
    CHECK_THAT(message, !Catch::Contains("18446744073709551615"));
  }
}

TEST_CASE("a header announcing more elements than the file holds is refused before allocating", "[io][mesh][bad]") {
  // Each of these 26..170-byte files announces about 10^9 elements; reading them once took 23 GB.
  CHECK_THROWS_WITH(read_mesh(data_file("bad/huge_header.off")),
                    Catch::Contains("huge_header.off: the header announces 999999999 vertices and 999999999 faces "
                                    "but the file has only 0 bytes after it"));
  CHECK_THROWS_WITH(read_mesh(data_file("bad/huge_header.ply")),
                    Catch::Contains("huge_header.ply: the header announces 999999999 'vertex' elements, "
                                    "999999999 'face' elements"));
  CHECK_THROWS_WITH(read_mesh(data_file("bad/huge_header.stl")),
                    Catch::Contains("huge_header.stl: the header announces 999999999 triangles"));
}

TEST_CASE("an OFF file cut short after a valid-looking size is refused with the missing element", "[io][mesh][bad]") {
  // Long lines pass the size check; the line check still finds the missing face.
  const auto file = write_text(scratch_dir("io_mesh_cut") / "cut.off",
                               "OFF\n3 2 0\n0.000000000 0.000000000 0.000000000\n1.000000000 0.000000000 0.000000000\n"
                               "0.000000000 1.000000000 0.000000000\n3 0 1 2\n");
  CHECK_THROWS_WITH(read_mesh(file), Catch::Contains("cut.off: the header announces 2 faces but the file ends after 1"));
  // Valid OFF variants are still read: counts on the keyword line, comments, per-vertex colours.
  const auto variant = write_text(scratch_dir("io_mesh_cut") / "variant.off",
                                  "OFF 3 1 0\n# comment\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK(read_mesh(variant).faces.size() == 1);
}
