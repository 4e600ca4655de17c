// Point-set I/O: .xyz/.pts, and PLY/OFF/OBJ without faces, read with or without normals; the
// mesh-or-points dispatch of an input file; the area estimate; errors with file and line.
#include "kernel_test_support.hpp"

#include <medax/io.hpp>

#include <random>

using namespace medax;
using medax::test::data_file;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace {

/// Uniform random points on the sphere of radius r, with their outward normals.
OrientedSamples random_sphere(std::size_t n, double r, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  OrientedSamples s;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    s.points.push_back(r * d);
    s.normals.push_back(d);
  }
  return s;
}

constexpr const char* kTetraPoints = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";

}  // namespace

TEST_CASE("write_point_set then read_point_set keeps points and unit normals", "[io][points]") {
  const OrientedSamples sphere = random_sphere(500, 2.0, 1);
  const auto dir = scratch_dir("io_points_round_trip");
  write_point_set(dir / "sphere.xyz", sphere);
  const OrientedSamples read = read_point_set(dir / "sphere.xyz");
  REQUIRE(read.size() == 500);
  REQUIRE(read.normals.size() == 500);
  REQUIRE(read.areas.size() == 500);
  double worst = 0;
  for (std::size_t i = 0; i < read.size(); ++i)
    worst = std::max({worst, (read.points[i] - sphere.points[i]).norm(), (read.normals[i] - sphere.normals[i]).norm()});
  CHECK(worst < 1e-15);
  OrientedSamples bare = sphere;
  bare.normals.clear();
  write_point_set(dir / "bare.pts", bare);
  const OrientedSamples read_bare = read_point_set(dir / "bare.pts");
  CHECK(read_bare.size() == 500);
  CHECK(read_bare.normals.empty());
}

TEST_CASE("the area estimate of a uniform sample is near the surface area, shared equally", "[io][points]") {
  const OrientedSamples sphere = random_sphere(4000, 1.5, 7);
  const double area = estimate_surface_area(sphere.points);
  CHECK(area == Approx(4 * M_PI * 1.5 * 1.5).epsilon(0.15));
  const auto file = scratch_dir("io_points_area") / "sphere.xyz";
  write_point_set(file, sphere);
  const OrientedSamples read = read_point_set(file);
  double sum = 0;
  for (double a : read.areas) sum += a;
  CHECK(sum == Approx(area).epsilon(1e-12));
  CHECK(read.areas.front() == read.areas.back());
  CHECK(estimate_surface_area({Vec3(0, 0, 0), Vec3(1, 0, 0)}) == 0);
}

TEST_CASE("PLY, OFF and OBJ files without faces are point sets, with or without normals", "[io][points]") {
  const auto dir = scratch_dir("io_points_formats");
  write_text(dir / "normals.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
             "property float nx\nproperty float ny\nproperty float nz\nend_header\n"
             "0 0 0 0 0 -2\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n");
  write_text(dir / "bare.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
             "end_header\n" + std::string(kTetraPoints));
  write_text(dir / "normals.off", "NOFF\n4 0 0\n0 0 0 0 0 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 3\n");
  write_text(dir / "colours.off", "COFF\n4 0 0\n0 0 0 9 9 9 1\n1 0 0 9 9 9 1\n0 1 0 9 9 9 1\n0 0 1 9 9 9 1\n");
  write_text(dir / "normals.obj", "# points\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nvn 1 0 0\nvn 0 1 0\n"
                                  "vn 0 0 1\n");
  write_text(dir / "counted.xyz", "4\n" + std::string(kTetraPoints));
  for (const std::string name : {"normals.ply", "bare.ply", "normals.off", "colours.off", "normals.obj",
                                 "counted.xyz"}) {
    INFO(name);
    CHECK(is_point_set_file(dir / name));
    const Shape shape = read_shape(dir / name);
    CHECK(shape.mesh.empty());
    CHECK(shape.source == (dir / name).string());
    REQUIRE(shape.samples.size() == 4);
    CHECK(shape.samples.points[3] == Vec3(0, 0, 1));
    const bool normals = name.rfind("normals", 0) == 0;
    REQUIRE(shape.samples.normals.size() == (normals ? 4u : 0u));
    if (normals) CHECK(shape.samples.normals[0] == Vec3(0, 0, -1));  // made unit
    if (normals) CHECK(shape.samples.normals[3] == Vec3(0, 0, 1));
  }
}

TEST_CASE("a binary vertex-only PLY is a point set", "[io][points]") {
  const auto file = scratch_dir("io_points_binary") / "points.ply";
  const OrientedSamples sphere = random_sphere(50, 1.0, 3);
  std::string body;
  for (const Vec3& p : sphere.points)
    for (int k = 0; k < 3; ++k) {
      const float v = static_cast<float>(p[k]);
      body.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
  write_text(file, "ply\nformat binary_little_endian 1.0\nelement vertex 50\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n" + body);
  const OrientedSamples read = read_point_set(file);
  REQUIRE(read.size() == 50);
  CHECK((read.points[49] - sphere.points[49]).norm() < 1e-6);
}

TEST_CASE("read_shape gives a mesh for a file with faces, and read_mesh keeps refusing points", "[io][points]") {
  const Shape cube = read_shape(data_file("cube.off"));
  CHECK(cube.mesh.faces.size() == 12);
  CHECK(cube.samples.empty());
  CHECK_FALSE(is_point_set_file(data_file("cube.off")));
  const auto dir = scratch_dir("io_points_dispatch");
  write_text(dir / "scan.xyz", kTetraPoints);
  CHECK_THROWS_WITH(read_mesh(dir / "scan.xyz"), Catch::Contains(".xyz and .pts files are point sets"));
  write_text(dir / "points.off", "OFF\n4 0 0\n" + std::string(kTetraPoints));
  CHECK_THROWS_WITH(read_mesh(dir / "points.off"), Catch::Contains("4 vertices and no faces"));
  CHECK(read_shape(dir / "points.off").samples.size() == 4);
  // A broken mesh file is left to read_mesh, whose error says what is wrong.
  write_text(dir / "broken.off", "OFF\n3 1 0\n0 0 0\n1 0\n");
  CHECK_FALSE(is_point_set_file(dir / "broken.off"));
  CHECK_THROWS_WITH(read_shape(dir / "broken.off"), Catch::Contains("broken.off"));
}

TEST_CASE("point-set errors name the file, the line and what to do", "[io][points]") {
  const auto dir = scratch_dir("io_points_errors");
  const auto error = [&](const std::string& name, const std::string& text) {
    write_text(dir / name, text);
    try {
      read_point_set(dir / name);
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error("four.xyz", "0 0 0\n1 0 0 5\n"), Catch::Contains("four.xyz: line 2: point 1 has 4 values but the "
                                                                    "first point has 3"));
  CHECK_THAT(error("two.xyz", "# header\n0 0\n"), Catch::Contains("two.xyz: line 2: 2 values; a point line is"));
  CHECK_THAT(error("word.xyz", "0 0 0\n1 zero 0\n"), Catch::Contains("line 2: vertex 1: 'zero' is not a number"));
  CHECK_THAT(error("nan.xyz", "0 0 nan\n"), Catch::Contains("line 1: vertex 0 has the non-finite coordinate"));
  CHECK_THAT(error("zero.xyz", "0 0 0 0 0 1\n1 0 0 0 0 0\n"),
             Catch::Contains("zero.xyz: line 2: point 1: the normal is zero") && Catch::Contains("`normals` stage"));
  CHECK_THAT(error("empty.xyz", ""), Catch::Contains("empty.xyz: empty file"));
  CHECK_THAT(error("comments.xyz", "# nothing\n"), Catch::Contains("no points in the file"));
  CHECK_THAT(error("vn.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\n"), Catch::Contains("1 'vn' lines for 2 'v' lines"));
  CHECK_THAT(error("faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
             Catch::Contains("faces.obj: line 4: a face: the file is a mesh"));
  CHECK_THAT(error("faces.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), Catch::Contains("1 faces: the file "
                                                                                               "is a mesh"));
  CHECK_THAT(error("short.off", "NOFF\n2 0 0\n0 0 0 0 0 1\n1 0 0\n"),
             Catch::Contains("short.off: line 4: vertex 1 has 3 value(s); a vertex line is 'x y z nx ny nz'"));
  CHECK_THAT(error("truncated.off", "OFF\n5 0 0\n0 0 0\n"), Catch::Contains("announces 5 vertices but the file "
                                                                            "ends after 1"));
  CHECK_THAT(error("shape.stl", "solid\n"), Catch::Contains("unsupported point-set format '.stl'"));
  CHECK_THAT(error("truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nend_header\n0 0 0\n"),
             Catch::Contains("truncated.ply"));
}
