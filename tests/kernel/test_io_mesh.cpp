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
