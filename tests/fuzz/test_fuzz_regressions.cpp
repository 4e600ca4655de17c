// Every seed and every input the fuzzers found a fault with, run through its reader: each is
// read or refused with medax's own error (IoError, PipelineError); anything else fails here.
#include "fuzz_input.hpp"

#include <medax/io.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using medax::fuzz::feed;
using medax::read_mesh;

namespace {

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// The files of tests/fuzz/<kind>/<target>/ (none when the folder does not exist).
std::vector<fs::path> inputs(const std::string& kind, const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(MEDAX_FUZZ_DIR) / kind / target;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

namespace {
/// Writes `bytes` to a scratch file named `name` and returns its path.
fs::path scratch_file(const std::string& name, const std::string& bytes) {
  const fs::path dir = fs::path(MEDAX_BINARY_DIR) / "tests" / "scratch" / "fuzz_messages";
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}
const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
}  // namespace

TEST_CASE("every seed and crasher is read or refused with medax's error", "[fuzz]") {
  std::size_t count = 0;
  for (const std::string& target : medax::fuzz::targets())
    for (const char* kind : {"corpus", "regressions"})
      for (const fs::path& file : inputs(kind, target)) {
        INFO(target << ": " << file.string());
        CHECK_NOTHROW(feed(target, bytes_of(file)));
        ++count;
      }
  CHECK(count > 30);
}

TEST_CASE("the seed meshes named ok_* are read, so the harnesses reach past the header", "[fuzz]") {
  for (const std::string& target : medax::fuzz::targets())
    for (const fs::path& file : inputs("corpus", target))
      if (file.filename().string().rfind("ok_", 0) == 0) {
        INFO(target << ": " << file.string());
        CHECK(feed(target, bytes_of(file)));
      }
}


TEST_CASE("the fixed findings are refused with the reason and the place", "[fuzz]") {
  const fs::path regressions = fs::path(MEDAX_FUZZ_DIR) / "regressions";
  // CGAL sized a face from a binary corner count (5.8 GB for a 142-byte file).
  CHECK_THROWS_WITH(read_mesh(regressions / "off" / "oom_binary_off_corner_count.off"),
                    Catch::Contains("line 1: binary OFF is not supported"));
  // fs::exists threw std::filesystem_error (a file name too long) for `input:`: a terminate.
  CHECK_FALSE(feed("pipeline", bytes_of(regressions / "pipeline" / "terminate_input_name_too_long.yaml")));
  // CGAL cast the colour 5520 to unsigned char (undefined); medax reads OFF itself, colours ignored.
  CHECK(read_mesh(regressions / "off" / "ub_coff_colour_out_of_range.off").vertices.size() == 4);
  // CGAL took the back() of an empty element list for a property before any element (the
  // mangled `element` keyword); every header line is now checked.
  CHECK_THROWS_WITH(read_mesh(regressions / "ply_ascii" / "ub_property_before_element.ply"),
                    Catch::Contains("line 3: 'e0t' is not a PLY header line"));
  CHECK_THROWS_WITH(read_mesh(regressions / "ply_binary" / "ub_property_before_element.ply"),
                    Catch::Contains("line 3: 'l0ement' is not a PLY header line"));
  // A second format line: the checks walked the body as little-endian, CGAL as big-endian, and
  // looped over a list count of 2^31 (a timeout).
  CHECK_THROWS_WITH(read_mesh(regressions / "ply_binary" / "timeout_second_format_line.ply"),
                    Catch::Contains("line 3: line 2 and only line 2 is 'format"));
  // `end_header#######` ended the header for the checks ('#' taken as a comment) but not for CGAL,
  // which then met a property before any element. PLY has no '#' comments: the '#'s of its
  // format line now make that line wrong.
  CHECK_THROWS_WITH(read_mesh(regressions / "ply_ascii" / "ub_hash_in_end_header.ply"),
                    Catch::Contains("line 2: a format line is"));
  CHECK_THROWS_WITH(read_mesh(scratch_file("early.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n")),
                    Catch::Contains("early.ply: line 3: a property comes before any 'element' line"));
  // A vertex-only PLY (a point set) with an integer coordinate: CGAL's point reader asserts
  // (terminate) on a coordinate or normal that is not float or double; now refused before it.
  CHECK_THROWS_WITH(medax::read_shape(regressions / "ply_ascii" / "assert_point_reader_uint8_z.ply"),
                    Catch::Contains("the vertex property 'z' is not a float or double"));
  CHECK_THROWS_WITH(medax::read_shape(regressions / "ply_binary" / "assert_point_reader_int16_z.ply"),
                    Catch::Contains("the vertex property 'z' is not a float or double"));
}

TEST_CASE("OFF variants: colours ignored, nOFF and binary OFF refused before any allocation", "[fuzz]") {
  const std::string tetra = "0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n0 0 1 1 1 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const auto coff = read_mesh(scratch_file("tetra.off", "COFF\n4 4 0\n" + tetra));
  CHECK(coff.vertices.size() == 4);
  CHECK(coff.faces.size() == 4);
  CHECK(coff.vertices[1].x() == 1.0);
  const auto homogeneous = read_mesh(scratch_file("tetra4.off", "4OFF\n4 4 0\n" + tetra));
  CHECK(homogeneous.vertices[1].x() == 1.0);  // w = 1
  CHECK_THROWS_WITH(read_mesh(scratch_file("n.off", "nOFF\n3\n4 4 0\n" + tetra)),
                    Catch::Contains("n.off: line 1: 'nOFF' (OFF with a dimension line) is not supported"));
  CHECK_THROWS_WITH(read_mesh(scratch_file("b.off", std::string("OFF BINARY\n\0\0\0\x04", 15))),
                    Catch::Contains("b.off: line 1: binary OFF is not supported"));
}

TEST_CASE("ASCII PLY body errors name the element, its index and the line", "[fuzz]") {
  CHECK_THROWS_WITH(read_mesh(scratch_file("short_row.ply", kPlyHeader + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n")),
                    Catch::Contains("short_row.ply: line 11: vertex 1: 'z' is missing"));
  CHECK_THROWS_WITH(read_mesh(scratch_file("word.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 x 2\n")),
                    Catch::Contains("word.ply: line 13: face 0: 'x' is not a vertex index"));
  CHECK_THROWS_WITH(read_mesh(scratch_file("big_list.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n")),
                    Catch::Contains("big_list.ply: line 13: face 0: 'vertex_indices' is missing (the line has 4 values)"));
  CHECK_THROWS_WITH(read_mesh(scratch_file("extra.ply", kPlyHeader + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n")),
                    Catch::Contains("extra.ply: line 10: vertex 0 has 4 values but the header declares 3"));
  const auto ok = read_mesh(scratch_file("ok.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  CHECK(ok.faces.size() == 1);
}

TEST_CASE("a binary PLY list count is checked against the bytes left", "[fuzz]") {
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nelement face 1\n"
                    "property list uint int vertex_indices\nend_header\n";
  ply += std::string("\xff\xff\xff\x7f", 4) + std::string(12, '\0');  // 2^31 - 1 corners, 3 given
  CHECK_THROWS_WITH(read_mesh(scratch_file("list.ply", ply)),
                    Catch::Contains("list.ply: face 0: 'vertex_indices' runs past the end of the file"));
}
