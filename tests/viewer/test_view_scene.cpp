// What the viewer reads from a run folder (framework/cli/view_scene.cpp): the medial complex
// with its fields, curves = edges bounding no triangle, the input surface, other surfaces.
#include "view_csv.hpp"
#include "view_scene.hpp"
#include "viewer_fixture.hpp"

#include <medax/io.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace medax::test;
using medax::cli::ViewField;
using medax::cli::ViewScene;

namespace {

const ViewField* find_field(const ViewScene& scene, const std::string& element, const std::string& name) {
  for (const ViewField& f : scene.fields)
    if (f.element == element && f.name == name) return &f;
  return nullptr;
}

void write_file(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

}  // namespace

TEST_CASE("the viewer's scene of a real run holds its medial complex, fields and input surface", "[viewer]") {
  const ViewScene scene = medax::cli::read_view_scene(small_run());
  const medax::MedialComplex mc = medax::read_ma(small_run() / "medial.ma");
  REQUIRE(scene.radii.size() == mc.centres.size());
  CHECK(scene.positions.size() == 3 * mc.centres.size());
  for (std::size_t i = 0; i < mc.centres.size(); i += 97) {
    CHECK(scene.radii[i] == Approx(mc.radii[i]).epsilon(1e-6));
    CHECK(scene.positions[3 * i + 2] == Approx(mc.centres[i].z()).epsilon(1e-6));
  }
  CHECK(scene.triangles.size() == 3 * mc.faces.size());
  // Curves: the edges of the .ma that bound no triangle, counted here independently.
  std::set<std::pair<medax::Index, medax::Index>> in_faces;
  for (const medax::Tri& f : mc.faces)
    for (int c = 0; c < 3; ++c) in_faces.insert(std::minmax(f[c], f[(c + 1) % 3]));
  const auto curves = std::count_if(mc.edges.begin(), mc.edges.end(),
                                    [&](const medax::Segment& e) { return !in_faces.count(std::minmax(e[0], e[1])); });
  CHECK(scene.curves.size() == 2 * static_cast<std::size_t>(curves));

  const ViewField* radius = find_field(scene, "vertex", "radius");
  REQUIRE(radius);
  CHECK(!radius->label);
  CHECK(radius->values.size() == mc.centres.size());
  const ViewField* polygon = find_field(scene, "face", "polygon");  // voronoi's face label
  REQUIRE(polygon);
  CHECK(polygon->label);
  CHECK(polygon->values.size() == mc.faces.size());

  REQUIRE(!scene.surfaces.empty());
  CHECK(scene.surfaces[0].id == "surface");
  CHECK(scene.surfaces[0].positions.size() == 3 * 162);  // tests/data/ellipsoid.off
  CHECK(scene.surfaces[0].triangles.size() == 3 * 320);
  CHECK(scene.notes.empty());
}

TEST_CASE("the viewer fans polygons, keeps a face field per triangle and an edge field per curve", "[viewer]") {
  const auto dir = scratch_dir("viewer_scene_ply");
  write_file(
      dir / "medial.ply",
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
      "property double radius\nproperty int sheet\nelement edge 2\nproperty int vertex1\nproperty int vertex2\n"
      "property double strength\nelement face 1\nproperty list uchar int vertex_indices\nproperty double angle\n"
      "end_header\n0 0 0 1 7\n1 0 0 1 7\n1 1 0 2 8\n0 1 0 2 8\n3 3 3 0.5 9\n0 1 0.25\n2 4 0.75\n4 0 1 2 3 1.5\n");
  write_file(
      dir / "durix_segmentation.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n");
  const ViewScene scene = medax::cli::read_view_scene(dir);
  CHECK(scene.triangles == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  CHECK(scene.curves == std::vector<std::uint32_t>{2, 4});  // 0-1 bounds the quad
  const ViewField* angle = find_field(scene, "face", "angle");
  REQUIRE(angle);
  CHECK(angle->values == std::vector<float>{1.5f, 1.5f});
  const ViewField* strength = find_field(scene, "edge", "strength");
  REQUIRE(strength);
  CHECK(strength->values == std::vector<float>{0.75f});
  const ViewField* sheet = find_field(scene, "vertex", "sheet");
  REQUIRE(sheet);
  CHECK(sheet->label);
  CHECK(sheet->values == std::vector<float>{7, 7, 8, 8, 9});
  // A stage's surface file is a layer of its own, with its colours.
  REQUIRE(scene.surfaces.size() == 1);
  CHECK(scene.surfaces[0].id == "durix_segmentation.ply");
  CHECK(scene.surfaces[0].colours == std::vector<std::uint8_t>{255, 0, 0, 0, 255, 0, 0, 0, 255});
  CHECK(scene.surfaces[0].field.name.empty());  // shown in its own colours
  // No config.resolved.yaml and no run.json: said, not hidden.
  CHECK(scene.notes.size() == 2);
}

TEST_CASE("the viewer refuses a folder without a medial complex and a binary PLY, saying what to do", "[viewer]") {
  const auto dir = scratch_dir("viewer_scene_bad");
  CHECK_THROWS_WITH(medax::cli::read_view_scene(dir), Catch::Contains("holds no medial.ply or medial.ma"));
  write_file(dir / "medial.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 0\nend_header\n");
  CHECK_THROWS_WITH(medax::cli::read_view_scene(dir), Catch::Contains("binary_little_endian PLY is not read"));
  write_file(dir / "medial.ply",
             "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
             "property double z\nproperty double radius\nend_header\n0 0 0 1\n");
  CHECK_THROWS_WITH(medax::cli::read_view_scene(dir), Catch::Contains("ends inside element 'vertex'"));
}

TEST_CASE("results.csv is read with its quoting: commas, quotes and line breaks inside a cell", "[viewer]") {
  const auto dir = scratch_dir("viewer_csv");
  write_file(dir / "results.csv", "job,status,error\n0001-a,ok,\n0002-b,failed,\"stage x: \"\"bad\"\", then\nmore\"\n");
  const auto rows = medax::cli::read_csv(dir / "results.csv");
  REQUIRE(rows.size() == 3);
  CHECK(rows[0] == std::vector<std::string>{"job", "status", "error"});
  CHECK(rows[1] == std::vector<std::string>{"0001-a", "ok", ""});
  CHECK(rows[2] == std::vector<std::string>{"0002-b", "failed", "stage x: \"bad\", then\nmore"});
  CHECK(!medax::cli::is_experiment_folder(dir));  // no jobs/ folder
}

TEST_CASE("a stage's point set and primitives are layers coloured by their own field", "[viewer]") {
  const auto dir = scratch_dir("viewer_scene_layers");
  write_file(dir / "medial.ma", "2 1 0\nv 0 0 0 1\nv 1 0 0 1\ne 0 1\n");
  // The reconstruction's envelope samples: points with normals, areas and their distance.
  write_file(dir / "reconstruction_envelope.ply",
             "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\nproperty double z\n"
             "property double nx\nproperty double ny\nproperty double nz\nproperty double area\n"
             "property double distance\nend_header\n0 0 1 0 0 1 0.5 0.01\n0 0 -1 0 0 -1 0.5 0.03\n");
  // MSD's primitives: triangles labelled by the primitive they belong to.
  write_file(dir / "msd_primitives.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
             "property double radius\nelement face 2\nproperty list uchar int vertex_indices\nproperty int primitive\n"
             "end_header\n0 0 0 1\n1 0 0 1\n0 1 0 1\n1 1 0 1\n3 0 1 2 4\n3 1 3 2 9\n");
  const ViewScene scene = medax::cli::read_view_scene(dir);
  REQUIRE(scene.surfaces.size() == 2);
  const auto& primitives = scene.surfaces[0];  // sorted by file name
  CHECK(primitives.id == "msd_primitives.ply");
  CHECK(primitives.field.name == "primitive");
  CHECK(primitives.field.element == "face");
  CHECK(primitives.field.label);
  CHECK(primitives.field.values == std::vector<float>{4, 9});
  const auto& envelope = scene.surfaces[1];
  CHECK(envelope.triangles.empty());  // a point set
  CHECK(envelope.positions.size() == 6);
  CHECK(envelope.field.name == "distance");
  CHECK(envelope.field.element == "vertex");
  CHECK(envelope.field.values == std::vector<float>{0.01f, 0.03f});
  CHECK(scene.curves == std::vector<std::uint32_t>{0, 1});  // the .ma's edge, in no triangle
}

TEST_CASE("the viewer reads a field value written as nan (undefined) and refuses a word that is not a number",
          "[viewer]") {
  const auto dir = scratch_dir("viewer_scene_nan");
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "property double radius\nproperty double et_c\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  write_file(dir / "medial.ply", header + "0 0 0 1 0.5\n1 0 0 1 nan\n1 1 0 1 -inf\n0 1 0 1 2\n3 0 1 2\n");
  const ViewScene scene = medax::cli::read_view_scene(dir);
  const ViewField* et_c = find_field(scene, "vertex", "et_c");
  REQUIRE(et_c);
  REQUIRE(et_c->values.size() == 4);
  CHECK(et_c->values[0] == 0.5f);
  CHECK(std::isnan(et_c->values[1]));
  CHECK(std::isinf(et_c->values[2]));  // not finite: the page gives it no colour
  CHECK(et_c->values[3] == 2.0f);
  write_file(dir / "medial.ply", header + "0 0 0 1 0.5\n1 0 0 1 x1\n1 1 0 1 1\n0 1 0 1 2\n3 0 1 2\n");
  CHECK_THROWS_WITH(medax::cli::read_view_scene(dir), Catch::Contains("row 1: a value is missing or not a number"));
}

TEST_CASE("the viewer shows a point-cloud input as its points", "[viewer]") {
  const auto dir = scratch_dir("viewer_scene_cloud");
  write_file(dir / "cloud.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n");
  write_file(dir / "config.resolved.yaml", "input: " + (dir / "cloud.xyz").string() + "\n");
  write_file(dir / "medial.ply",
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\nproperty double z\n"
             "property double radius\nend_header\n0.5 0.5 0.5 0.4\n");
  const ViewScene scene = medax::cli::read_view_scene(dir);
  REQUIRE_FALSE(scene.surfaces.empty());
  CHECK(scene.surfaces[0].name == "input point cloud");
  CHECK(scene.surfaces[0].triangles.empty());
  CHECK(scene.surfaces[0].positions.size() == 15);
}

namespace {

/// An axis-aligned cube of half-side `h` centred at the origin, as OFF.
std::string cube_off(double h) {
  std::string text = "OFF\n8 12 0\n";
  for (int i = 0; i < 8; ++i)
    text += fmt::format("{} {} {}\n", i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  for (const char* f : {"0 2 1", "1 2 3", "4 5 6", "5 7 6", "0 1 4", "1 5 4", "2 6 3", "3 6 7", "0 4 2", "2 4 6",
                        "1 3 5", "3 7 5"})
    text += std::string("3 ") + f + "\n";
  return text;
}

}  // namespace

TEST_CASE("the viewer colours the reconstruction by its distance to the input surface", "[viewer]") {
  const auto dir = scratch_dir("viewer_scene_reconstruction");
  write_file(dir / "cube.off", cube_off(1.0));
  write_file(dir / "msd_reconstruction.off", cube_off(1.1));
  write_file(dir / "config.resolved.yaml", "input: " + (dir / "cube.off").string() + "\n");
  write_file(dir / "medial.ply",
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\nproperty double z\n"
             "property double radius\nend_header\n0 0 0 1\n");
  const ViewScene scene = medax::cli::read_view_scene(dir);
  const auto rebuilt = std::find_if(scene.surfaces.begin(), scene.surfaces.end(),
                                    [](const auto& s) { return s.id == "reconstruction"; });
  REQUIRE(rebuilt != scene.surfaces.end());
  CHECK(rebuilt->field.name == "distance to the input surface");
  REQUIRE(rebuilt->field.values.size() == 8);
  for (float d : rebuilt->field.values) CHECK(d == Approx(std::sqrt(3.0) * 0.1).epsilon(1e-5));  // corner to corner
}
