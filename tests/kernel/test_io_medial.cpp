// Medial complex I/O: .ma round trip and error positions, PLY with fields, OBJ.
#include "kernel_test_support.hpp"

#include <medax/io.hpp>

#include <cmath>
#include <sstream>

using namespace medax;
using medax::test::read_text;
using medax::test::scratch_dir;
using medax::test::write_text;

namespace {

/// A small non-manifold complex: three triangles on one edge, a dangling edge, awkward doubles,
/// fields and labels on every element kind.
MedialComplex sample_complex() {
  MedialComplex m;
  m.add_vertex(Vec3(0.1, -0.2, 1.0 / 3.0), 0.25);
  m.add_vertex(Vec3(1e-300, 2.5e17, -0.0), std::sqrt(2.0));
  m.add_vertex(Vec3(-7, 0.30000000000000004, 123456.789), 1e-9);
  m.add_vertex(Vec3(3, 3, 3), 0);
  m.add_vertex(Vec3(M_PI, -M_E, 1), 4);
  m.add_edge(0, 1);
  m.add_edge(3, 4);
  m.add_face(0, 1, 2);
  m.add_face(0, 1, 3);
  m.add_face(1, 0, 4);
  m.vertex_props.fields.add("erosion thickness", 5, 0.5)[2] = 1.0 / 7.0;
  m.vertex_props.labels.add("sheet", 5, 1)[4] = -3;
  m.edge_props.fields.add("length", 2, 2.0);
  m.face_props.labels.add("part", 3, 9);
  return m;
}

/// Lines of `text` from the one starting with `first` up to (excluding) `end_header`.
std::vector<std::string> header_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line) && line != "end_header";) lines.push_back(line);
  return lines;
}

std::string ma_error(const std::string& name, const std::string& contents) {
  const auto file = write_text(scratch_dir("io_ma_errors_" + name) / (name + ".ma"), contents);
  try {
    read_ma(file);
  } catch (const IoError& e) {
    return e.what();
  }
  FAIL("read_ma accepted " << name);
  return {};
}

}  // namespace

TEST_CASE(".ma write then read gives the same complex with exact doubles", "[io][ma]") {
  const auto dir = scratch_dir("io_ma_round_trip");
  const MedialComplex original = sample_complex();
  write_ma(dir / "m.ma", original);
  const MedialComplex read = read_ma(dir / "m.ma");
  CHECK(read.centres == original.centres);  // exact, not approximate
  CHECK(read.radii == original.radii);
  CHECK(read.edges == original.edges);
  CHECK(read.faces == original.faces);
  // .ma carries no properties.
  CHECK(read.vertex_props.fields.empty());

  const std::string text = read_text(dir / "m.ma");
  CHECK(text.rfind("5 2 3\nv ", 0) == 0);
  CHECK_THAT(text, Catch::Contains("\ne 3 4\n"));
  CHECK_THAT(text, Catch::Contains("\nf 1 0 4\n"));
  // Writing what was read gives the same bytes.
  write_ma(dir / "again.ma", read);
  CHECK(read_text(dir / "again.ma") == text);
}

TEST_CASE(".ma reading accepts comments and blank lines", "[io][ma]") {
  const auto file = write_text(scratch_dir("io_ma_comments") / "c.ma",
                               "# written by hand\n\n2 1 0  # counts\nv 0 0 0 1\n\nv 1 0 0 2\ne 0 1\n");
  const MedialComplex m = read_ma(file);
  CHECK(m.num_vertices() == 2);
  CHECK(m.radii[1] == 2.0);
  CHECK(m.edges.size() == 1);
}

TEST_CASE(".ma reading ignores extra trailing numbers on element lines (deleted/feature flags)", "[io][ma]") {
  const auto file = write_text(scratch_dir("io_ma_flags") / "flags.ma",
                               "# flagged variant\n3 2 1\nv 0 0 0 1 0\nv 1 0 0 2 0  # comment\nv 0 1 0 3 1\n"
                               "e 0 1 1\ne 1 2 0\nf 0 1 2 0\n");
  const MedialComplex m = read_ma(file);
  CHECK(m.radii == std::vector<double>{1, 2, 3});
  CHECK(m.edges == std::vector<Segment>{{0, 1}, {1, 2}});
  CHECK(m.faces == std::vector<Tri>{{0, 1, 2}});
  CHECK_THROWS_WITH(read_ma(write_text(scratch_dir("io_ma_flags") / "word.ma", "1 0 0\nv 0 0 0 1 deleted\n")),
                    Catch::Contains("word.ma:2: 'deleted' is not a number"));
}

TEST_CASE(".ma errors name the file and line", "[io][ma]") {
  SECTION("bad count header") {
    const auto e = ma_error("header", "2 1\nv 0 0 0 1\n");
    CHECK_THAT(e, Catch::Contains("header.ma:1:"));
    CHECK_THAT(e, Catch::Contains("nv ne nf"));
  }
  SECTION("non-number") {
    const auto e = ma_error("word", "1 0 0\n\nv 0 zero 0 1\n");
    CHECK_THAT(e, Catch::Contains("word.ma:3:"));
    CHECK_THAT(e, Catch::Contains("'zero' is not a number"));
  }
  SECTION("index out of range") {
    const auto e = ma_error("index", "2 1 0\nv 0 0 0 1\nv 1 0 0 1\ne 0 2\n");
    CHECK_THAT(e, Catch::Contains("index.ma:4:"));
    CHECK_THAT(e, Catch::Contains("vertex index 2 is not in 0..1"));
  }
  SECTION("negative radius") {
    CHECK_THAT(ma_error("radius", "1 0 0\nv 0 0 0 -1\n"), Catch::Contains("radius.ma:2:"));
  }
  SECTION("unknown line type") {
    CHECK_THAT(ma_error("tag", "1 0 0\nv 0 0 0 1\nx 1 2\n"), Catch::Contains("tag.ma:3: unknown line type 'x'"));
  }
  SECTION("counts that do not match the header") {
    // Long enough for the size check, so the counts are compared after reading.
    CHECK_THAT(ma_error("counts", "2 0 0\nv 0.000 0.000 0.000 1.000\n"), Catch::Contains("announces 2 0 0"));
    // Too short for the announced vertices: refused from the size, before reading.
    CHECK_THAT(ma_error("short", "2 0 0\nv 0 0 0 1\n"), Catch::Contains("short.ma:1: the header announces 2 vertices"));
  }
  SECTION("non-finite numbers") {
    CHECK_THAT(ma_error("inf", "2 1 0\nv 0 0 0 1\nv inf 0 0 1\ne 0 1\n"),
               Catch::Contains("inf.ma:3: 'inf' is not a finite number"));
    CHECK_THAT(ma_error("nan", "1 0 0\nv 0 0 0 nan\n"), Catch::Contains("nan.ma:2: 'nan' is not a finite number"));
    CHECK_THAT(ma_error("flag", "2 1 0\nv 0 0 0 1\nv 1 0 0 1\ne 0 1 -inf\n"),
               Catch::Contains("flag.ma:4: '-inf' is not a finite number"));
  }
  SECTION("a header announcing more than the file holds, before allocating") {
    // Reading this 30-byte file once reserved ~24 GB.
    const auto e = ma_error("huge", "999999999 999999999 999999999\n");
    CHECK_THAT(e, Catch::Contains("huge.ma:1: the header announces 999999999 vertices, 999999999 edges and "
                                  "999999999 faces but the file has only 30 bytes"));
    CHECK_THROWS_WITH(read_ma(medax::test::data_file("bad/huge_header.ma")),
                      Catch::Contains("huge_header.ma:1: the header announces 999999999 vertices"));
    CHECK_THROWS_WITH(read_ma(medax::test::data_file("bad/inf.ma")), Catch::Contains("inf.ma:3: 'inf' is not a finite"));
    CHECK_THROWS_WITH(read_ma(medax::test::data_file("bad/nan_radius.ma")),
                      Catch::Contains("nan_radius.ma:3: 'nan' is not a finite"));
    CHECK_THAT(ma_error("enormous", "1e300 0 0\n"), Catch::Contains("enormous.ma:1: counts must be whole numbers"));
  }
  SECTION("missing file") {
    CHECK_THROWS_WITH(read_ma(scratch_dir("io_ma_missing") / "none.ma"), Catch::Contains("none.ma: cannot open"));
  }
}

TEST_CASE("PLY output has radius and fields and labels as properties with the right counts", "[io][ply]") {
  const auto dir = scratch_dir("io_ply");
  write_medial_ply(dir / "m.ply", sample_complex());
  const std::string text = read_text(dir / "m.ply");
  CHECK(header_lines(text) == std::vector<std::string>{
                                  "ply", "format ascii 1.0", "comment medax medial complex",
                                  "element vertex 5", "property double x", "property double y", "property double z",
                                  "property double radius", "property double erosion_thickness", "property int sheet",
                                  "element edge 2", "property int vertex1", "property int vertex2",
                                  "property double length",
                                  "element face 3", "property list uchar int vertex_indices", "property int part"});
  // One body line per element, each with its property values.
  std::istringstream body(text.substr(text.find("end_header\n") + 11));
  std::vector<std::string> lines;
  for (std::string line; std::getline(body, line);) lines.push_back(line);
  REQUIRE(lines.size() == 5 + 2 + 3);
  CHECK(lines[0] == "0.1 -0.2 0.3333333333333333 0.25 0.5 1");
  CHECK(lines[4] == "3.141592653589793 -2.718281828459045 1 4 0.5 -3");
  CHECK(lines[5] == "0 1 2");
  CHECK(lines[9] == "3 1 0 4 9");
}

TEST_CASE("OBJ output has 1-based vertices lines and faces", "[io][obj]") {
  const auto dir = scratch_dir("io_obj");
  write_medial(dir / "m.obj", sample_complex());
  const std::string text = read_text(dir / "m.obj");
  std::istringstream in(text);
  std::size_t v = 0, l = 0, f = 0;
  for (std::string line; std::getline(in, line);) {
    v += line.rfind("v ", 0) == 0;
    l += line.rfind("l ", 0) == 0;
    f += line.rfind("f ", 0) == 0;
  }
  CHECK(v == 5);
  CHECK(l == 2);
  CHECK(f == 3);
  CHECK_THAT(text, Catch::Contains("\nl 4 5\n"));
  CHECK_THAT(text, Catch::Contains("\nf 2 1 5\n"));
}

TEST_CASE("read_medial and write_medial dispatch on the extension", "[io]") {
  const auto dir = scratch_dir("io_medial_dispatch");
  write_medial(dir / "m.MA", sample_complex());
  CHECK(read_medial(dir / "m.MA").num_vertices() == 5);
  CHECK_THROWS_WITH(write_medial(dir / "m.vtk", sample_complex()), Catch::Contains("unsupported medial format"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.vtk"));
  CHECK_THROWS_WITH(read_medial(dir / "m.ply"), Catch::Contains("read from .ma files"));
}
