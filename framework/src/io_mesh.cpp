// Surface mesh I/O: ASCII OFF read here; OBJ, PLY and STL through CGAL's polygon-soup readers after
// checks of their own; writers through CGAL.
#include "io_text.hpp"

#include <medax/io.hpp>

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

namespace medax {

namespace fs = std::filesystem;
using Point = CGAL::Simple_cartesian<double>::Point_3;

namespace {

using detail::coordinate;
using detail::fail;
using detail::Lines;
using detail::lower_extension;
using detail::parse_integer;
using detail::read_all;

void require_mesh_extension(const fs::path& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
    throw IoError(fmt::format("{}: unsupported mesh format '{}' (use .off, .obj, .ply or .stl){}", path.string(),
                              ext, ext == ".xyz" || ext == ".pts" ? "; .xyz and .pts files are point sets" : ""));
}

/// A declared element count that the file cannot hold: refused before anything is allocated.
void check_counts_fit(const fs::path& path, const std::string& announced, long double needed, std::uintmax_t bytes) {
  if (needed > static_cast<long double>(bytes))
    fail(path, fmt::format("the header announces {} but the file has only {} bytes after it (at least {:.0f} "
                           "needed): the file is truncated or its header is wrong; re-export the mesh",
                           announced, bytes, static_cast<double>(needed)));
}

using Polygons = std::vector<std::vector<std::size_t>>;

/// ASCII OFF read here, not by CGAL (whose scanner trusts counts and turns out-of-range colours
/// into undefined behaviour): header counts against the file size, then every vertex (3 finite
/// coordinates, or 4 homogeneous ones for 4OFF; colours, normals and texture coordinates after
/// them are ignored) and face (corner count, indices in range) with its line. Binary OFF and nOFF
/// are refused.
/// The OFF keyword line, if any: the coordinates per vertex (3, or 4 for 4OFF); leaves `t` on
/// the tokens of the counts line and returns where the counts start in it.
std::size_t read_off_keyword(const fs::path& path, Lines& lines, std::vector<std::string_view>& t,
                             std::size_t& dimension) {
  dimension = 3;
  if (!lines.next(t)) fail(path, "the file holds only blank lines and comments; an OFF file starts with 'OFF'");
  if (t[0].size() < 3 || t[0].substr(t[0].size() - 3) != "OFF") return 0;
  const std::string_view keyword = t[0];
  if (keyword.find('4') != std::string_view::npos) dimension = 4;
  if (t.size() > 1 && t[1] == "BINARY")
    fail(path, fmt::format("line {}: binary OFF is not supported; convert the mesh to ASCII OFF, PLY or STL "
                           "(e.g. with meshlabserver or CGAL's write_OFF)",
                           lines.line()));
  if (keyword.find('n') != std::string_view::npos)
    fail(path, fmt::format("line {}: '{}' (OFF with a dimension line) is not supported; write it as plain 'OFF' "
                           "with 3 coordinates per vertex",
                           lines.line(), keyword));
  if (t.size() > 1) return 1;
  if (!lines.next(t)) fail(path, "the file ends after 'OFF'; the counts 'vertices faces edges' are missing");
  return 0;
}

void read_off_vertex(const fs::path& path, const std::vector<std::string_view>& t, std::size_t line, long long v,
                     std::size_t dimension, std::vector<Point>& points) {
  if (t.size() < dimension)
    fail(path, fmt::format("line {}: vertex {} has {} coordinate(s); a vertex line is '{}'", line, v, t.size(),
                           dimension == 3 ? "x y z" : "x y z w"));
  double xyzw[4] = {0, 0, 0, 1};
  for (std::size_t k = 0; k < dimension; ++k) xyzw[k] = coordinate(path, t[k], line, static_cast<std::size_t>(v));
  points.emplace_back(xyzw[0] / xyzw[3], xyzw[1] / xyzw[3], xyzw[2] / xyzw[3]);
}

void read_off_face(const fs::path& path, const std::vector<std::string_view>& t, std::size_t line, long long f,
                   long long nv, Polygons& polygons) {
  long long n = 0;
  if (!parse_integer(t[0], n) || n < 0)
    fail(path, fmt::format("line {}: face {}: '{}' is not a corner count", line, f, t[0]));
  if (static_cast<long long>(t.size()) - 1 < n)
    fail(path, fmt::format("line {}: face {} announces {} corners but lists only {}", line, f, n, t.size() - 1));
  if (n < 3) fail(path, fmt::format("line {}: face {} has {} corners; a face needs at least 3", line, f, n));
  std::vector<std::size_t>& polygon = polygons.emplace_back();
  for (long long k = 1; k <= n; ++k) {
    long long index = 0;
    if (!parse_integer(t[k], index))
      fail(path, fmt::format("line {}: face {}: '{}' is not a vertex index", line, f, t[k]));
    if (index < 0 || index >= nv)
      fail(path, fmt::format("line {}: face {} refers to vertex {} but the vertices are 0..{}", line, f, index,
                             nv - 1));
    polygon.push_back(static_cast<std::size_t>(index));
  }
}

/// ASCII OFF read here, not by CGAL (whose scanner trusts counts and turns out-of-range colours
/// into undefined behaviour): header counts against the file size, then every vertex (3 finite
/// coordinates, or 4 homogeneous ones for 4OFF; colours, normals and texture coordinates after
/// them are ignored) and face (corner count, indices in range) with its line. Binary OFF and nOFF
/// are refused.
void read_off(const fs::path& path, const std::string& text, std::vector<Point>& points, Polygons& polygons) {
  Lines lines(text);
  std::vector<std::string_view> t;
  std::size_t dimension = 3;
  const std::size_t first = read_off_keyword(path, lines, t, dimension);
  long long nv = 0, nf = 0;
  if (t.size() < first + 2 || !parse_integer(t[first], nv) || !parse_integer(t[first + 1], nf) || nv < 0 || nf < 0)
    fail(path, fmt::format("line {}: expected the counts 'vertices faces edges' (whole numbers >= 0)", lines.line()));
  const std::uintmax_t rest = text.size() - lines.offset();
  // A vertex line takes at least 6 bytes ("0 0 0\n"), a face line 8 ("3 0 1 2\n"); binary takes more.
  check_counts_fit(path, fmt::format("{} vertices and {} faces", nv, nf), 6.0L * nv + 8.0L * nf - 1, rest);
  const auto next_line = [&](const char* what, long long announced, long long read) {
    if (!lines.next(t))
      fail(path, fmt::format("the header announces {} {} but the file ends after {} (line {}): the file is truncated",
                             announced, what, read, lines.line()));
  };
  for (long long v = 0; v < nv; ++v) {
    next_line("vertices", nv, v);
    read_off_vertex(path, t, lines.line(), v, dimension, points);
  }
  for (long long f = 0; f < nf; ++f) {
    next_line("faces", nf, f);
    read_off_face(path, t, lines.line(), f, nv, polygons);
  }
}

/// OBJ explained after CGAL refused it: the first bad vertex or face with its line, or no faces.
void explain_obj(const fs::path& path, const std::string& text) {
  Lines count_lines(text);
  std::vector<std::string_view> t;
  long long total = 0;
  while (count_lines.next(t)) total += t[0] == "v";
  Lines lines(text);
  long long nv = 0, nf = 0;
  while (lines.next(t)) {
    if (t[0] == "v") {
      if (t.size() < 4)
        fail(path, fmt::format("line {}: vertex {} has {} coordinate(s); a vertex line is 'v x y z'", lines.line(),
                               nv, t.size() - 1));
      for (int k = 1; k <= 3; ++k) coordinate(path, t[k], lines.line(), static_cast<std::size_t>(nv));
      ++nv;
    } else if (t[0] == "f") {
      if (t.size() < 4)
        fail(path, fmt::format("line {}: face {} has {} corners; a face needs at least 3", lines.line(), nf,
                               t.size() - 1));
      for (std::size_t k = 1; k < t.size(); ++k) {
        long long index = 0;
        const std::string_view word = t[k].substr(0, t[k].find('/'));
        if (!parse_integer(word, index) || index == 0)
          fail(path, fmt::format("line {}: face {}: '{}' is not a vertex index (1-based, or negative to count back)",
                                 lines.line(), nf, t[k]));
        const long long zero_based = index > 0 ? index - 1 : nv + index;
        if (zero_based < 0 || zero_based >= total)
          fail(path, fmt::format("line {}: face {} refers to vertex {} but the vertices are 1..{}", lines.line(), nf,
                                 index, total));
      }
      ++nf;
    }
  }
  if (nf == 0)
    fail(path, fmt::format("{} vertices and no faces ('f' lines): medax needs a triangle surface, not points", nv));
}

/// ASCII STL explained after CGAL refused it: the first bad 'vertex' line, or a facet that does
/// not have 3 vertices (a truncated file).
void explain_stl(const fs::path& path, const std::string& text) {
  Lines lines(text);
  std::vector<std::string_view> t;
  std::size_t facet = 0, corners = 0, vertex = 0;
  bool solid = false, open = false;
  while (lines.next(t)) {
    if (t[0] == "solid") solid = true;
    if (!solid) return;  // binary
    if (t[0] == "facet") {
      open = true;
      corners = 0;
    } else if (t[0] == "vertex") {
      if (t.size() < 4)
        fail(path, fmt::format("line {}: facet {}: a vertex line is 'vertex x y z'", lines.line(), facet));
      for (int k = 1; k <= 3; ++k) coordinate(path, t[k], lines.line(), vertex);
      ++vertex;
      ++corners;
    } else if (t[0] == "endfacet") {
      if (corners != 3)
        fail(path, fmt::format("line {}: facet {} has {} vertices; an STL facet has 3", lines.line(), facet, corners));
      open = false;
      ++facet;
    }
  }
  if (open) fail(path, fmt::format("facet {} is not closed by 'endfacet': the file is truncated", facet));
}

/// A PLY header: the elements with their properties, the format and where the body starts.
struct PlyProperty {
  std::string name;
  bool real = false;   ///< a float or double scalar (CGAL's point reader asserts on anything else)
  int size = 4;        ///< bytes of a value (binary)
  int count_size = 0;  ///< bytes of a list's count; 0 for a scalar
  bool count_signed = false;
};
struct PlyHeaderElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  bool ascii = false;
  bool big_endian = false;
  std::vector<PlyHeaderElement> elements;
  std::size_t body = 0;       ///< offset of the first byte after `end_header`
  std::size_t body_line = 0;  ///< lines before the body
};

/// Bytes of a PLY value type; 0 for a name that is not a PLY type.
int ply_type_size(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

/// One `property` line: 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'.
PlyProperty ply_property(const fs::path& path, const std::vector<std::string_view>& t, std::size_t line) {
  const bool list = t.size() == 5 && t[1] == "list";
  PlyProperty property;
  property.name = std::string(t.back());
  property.size = ply_type_size(t[list ? 3 : 1]);
  property.real = !list && (t[1] == "float" || t[1] == "float32" || t[1] == "double" || t[1] == "float64");
  if (list) {
    property.count_size = ply_type_size(t[2]);
    property.count_signed = t[2] == "char" || t[2] == "int8" || t[2] == "short" || t[2] == "int16" || t[2] == "int" ||
                            t[2] == "int32";
  }
  if ((t.size() != 3 && !list) || property.size == 0 || (list && property.count_size == 0))
    fail(path, fmt::format("line {}: a property line is 'property TYPE NAME' or 'property list COUNT_TYPE TYPE "
                           "NAME', TYPE one of char uchar short ushort int uint float double",
                           line));
  return property;
}

/// The header, checked line by line (CGAL trusts it: a property before any element made it read
/// out of bounds).
PlyHeader read_ply_header(const fs::path& path, const std::string& text) {
  if (text.rfind("ply", 0) != 0) fail(path, "not a PLY file: it must start with 'ply'");
  PlyHeader header;
  Lines lines(text, false);
  std::vector<std::string_view> t;
  for (;;) {
    if (!lines.next(t)) fail(path, "the PLY header has no 'end_header' line");
    const std::string_view keyword = t[0];
    // CGAL takes line 2 as the format whatever its keyword (even 'end_header'), and the format
    // from line 2 only: anything else would make it read the file differently from the checks here.
    if ((lines.line() == 2) != (keyword == "format"))
      fail(path, fmt::format("line {}: line 2 and only line 2 is 'format ascii|binary_little_endian|"
                             "binary_big_endian 1.0'",
                             lines.line()));
    if (keyword == "end_header") break;
    if (keyword == "format") {
      header.ascii = t.size() == 3 && t[1] == "ascii";
      header.big_endian = t.size() == 3 && t[1] == "binary_big_endian";
      if (t.size() != 3 || (!header.ascii && !header.big_endian && t[1] != "binary_little_endian"))
        fail(path, fmt::format("line {}: a format line is 'format ascii|binary_little_endian|binary_big_endian 1.0'",
                               lines.line()));
    } else if (keyword == "element") {
      long long n = 0;
      if (t.size() != 3 || !parse_integer(t[2], n) || n < 0)
        fail(path, fmt::format("line {}: an element line is 'element NAME COUNT'", lines.line()));
      header.elements.push_back({std::string(t[1]), n, {}});
    } else if (keyword == "property") {
      if (header.elements.empty())
        fail(path, fmt::format("line {}: a property comes before any 'element' line", lines.line()));
      header.elements.back().properties.push_back(ply_property(path, t, lines.line()));
    } else if (keyword != "ply" && keyword != "comment" && keyword != "obj_info") {
      fail(path, fmt::format("line {}: '{}' is not a PLY header line (format, element, property, comment, "
                             "end_header)",
                             lines.line(), keyword));
    }
  }
  header.body = lines.offset();
  header.body_line = lines.line();
  return header;
}

/// Element counts against the bytes after the header (ASCII: 2 bytes per property at least;
/// binary: the property sizes, a list its count), before anything is walked or allocated.
void check_ply_counts(const fs::path& path, const std::string& text, const PlyHeader& header) {
  long double needed = 0;
  std::string announced;
  for (const PlyHeaderElement& e : header.elements) {
    long double bytes = 0;
    for (const PlyProperty& p : e.properties) bytes += header.ascii ? 2 : (p.count_size ? p.count_size : p.size);
    needed += static_cast<long double>(e.count) * std::max<long double>(bytes, 1);
    announced += fmt::format("{}{} '{}' elements", announced.empty() ? "" : ", ", e.count, e.name);
  }
  check_counts_fit(path, announced, needed - 1, text.size() - header.body);
}

long long vertex_count(const PlyHeader& header) {
  for (const PlyHeaderElement& e : header.elements)
    if (e.name == "vertex") return e.count;
  return 0;
}

/// ASCII body: one line per element with the values its properties declare, coordinates finite,
/// face indices in range; errors name the line and the element index.
void check_ply_ascii_body(const fs::path& path, const std::string& text, const PlyHeader& header) {
  Lines lines(std::string_view(text).substr(header.body), false);
  std::vector<std::string_view> t;
  const long long nv = vertex_count(header);
  const auto where = [&](const PlyHeaderElement& e, long long i) {
    return fmt::format("line {}: {} {}", header.body_line + lines.line(), e.name, i);
  };
  for (const PlyHeaderElement& e : header.elements)
    for (long long i = 0; i < e.count; ++i) {
      if (!lines.next(t))
        fail(path, fmt::format("the header announces {} '{}' elements but the file ends after {}: the file is "
                               "truncated",
                               e.count, e.name, i));
      std::size_t k = 0;
      for (const PlyProperty& p : e.properties) {
        long long n = 1;
        if (p.count_size && (k >= t.size() || !parse_integer(t[k++], n) || n < 0))
          fail(path, fmt::format("{}: the list '{}' needs a count >= 0", where(e, i), p.name));
        for (long long j = 0; j < n; ++j, ++k) {
          if (k >= t.size())
            fail(path, fmt::format("{}: '{}' is missing (the line has {} values)", where(e, i), p.name, t.size()));
          long long index = 0;
          if (p.count_size && p.name.rfind("vertex_ind", 0) == 0 && !parse_integer(t[k], index))
            fail(path, fmt::format("{}: '{}' is not a vertex index", where(e, i), t[k]));
          if (p.count_size && p.name.rfind("vertex_ind", 0) == 0 && (index < 0 || index >= nv))
            fail(path, fmt::format("{} {} refers to vertex {} but the vertices are 0..{} (line {})", e.name, i, index,
                                   nv - 1, header.body_line + lines.line()));
          if (!p.count_size && e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z"))
            coordinate(path, t[k], header.body_line + lines.line(), static_cast<std::size_t>(i));
        }
      }
      if (k != t.size())
        fail(path, fmt::format("{} has {} values but the header declares {}", where(e, i), t.size(), k));
    }
}

/// Binary body: every list count checked against the bytes left, so no count is trusted.
void check_ply_binary_body(const fs::path& path, const std::string& text, const PlyHeader& header) {
  std::size_t at = header.body;
  const auto read_count = [&](const PlyProperty& p) -> long long {
    unsigned char bytes[8] = {};
    std::memcpy(bytes, text.data() + at, static_cast<std::size_t>(p.count_size));
    unsigned long long value = 0;
    for (int b = 0; b < p.count_size; ++b)
      value |= static_cast<unsigned long long>(bytes[header.big_endian ? p.count_size - 1 - b : b]) << (8 * b);
    const unsigned long long sign = 1ULL << (8 * p.count_size - 1);
    return p.count_signed && (value & sign) ? -1 : static_cast<long long>(value);
  };
  for (const PlyHeaderElement& e : header.elements)
    for (long long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        const std::size_t left = text.size() - std::min(at, text.size());
        long long n = 1;
        if (p.count_size) {
          if (left < static_cast<std::size_t>(p.count_size)) n = -2;
          else n = read_count(p), at += static_cast<std::size_t>(p.count_size);
        }
        if (n == -1) fail(path, fmt::format("{} {}: the list '{}' has a negative count", e.name, i, p.name));
        const long double bytes = static_cast<long double>(std::max(n, 0LL)) * p.size;
        if (n == -2 || bytes > static_cast<long double>(text.size() - std::min(at, text.size())))
          fail(path, fmt::format("{} {}: '{}' runs past the end of the file (byte {}): the file is truncated or "
                                 "a list count is wrong",
                                 e.name, i, p.name, at));
        at += static_cast<std::size_t>(bytes);
      }
}

PlyHeader check_ply(const fs::path& path, const std::string& text) {
  const PlyHeader header = read_ply_header(path, text);
  check_ply_counts(path, text, header);
  if (header.ascii) check_ply_ascii_body(path, text, header);
  else check_ply_binary_body(path, text, header);
  return header;
}

/// Binary STL: the triangle count against the file size (50 bytes a triangle after 84).
void check_stl(const fs::path& path, const std::string& text) {
  std::size_t i = 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  if (text.compare(i, 5, "solid") == 0) return;  // ASCII: nothing is allocated ahead
  if (text.size() < 84)
    fail(path, fmt::format("a binary STL starts with an 84-byte header but the file has only {} bytes", text.size()));
  std::uint32_t n = 0;
  std::memcpy(&n, text.data() + 80, 4);
  if (84 + 50ULL * n != text.size())
    check_counts_fit(path, fmt::format("{} triangles", n), 50.0L * n, text.size() - 84);
}

/// OBJ, PLY and STL through CGAL's polygon soup reader (after the checks above for PLY and STL).
void read_with_cgal(const fs::path& path, const std::string& ext, std::vector<Point>& points, Polygons& polygons) {
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path.string(), points, polygons, CGAL::parameters::verbose(false));
  } catch (const std::bad_alloc&) {
    fail(path, "out of memory while reading: the file announces more elements than it holds, or is too large");
  } catch (const std::exception& e) {
    fail(path, fmt::format("cannot parse as {}: {}", ext.substr(1), e.what()));
  }
  if (!ok) {
    if (ext == ".obj") explain_obj(path, read_all(path));
    if (ext == ".stl") explain_stl(path, read_all(path));
    throw IoError(fmt::format("{}: cannot parse as {} (is the file complete and well formed?)",
                              path.string(), ext.substr(1)));
  }
}

}  // namespace

detail::PlyContents detail::check_ply_contents(const fs::path& path, const std::string& text) {
  const PlyHeader header = check_ply(path, text);
  PlyContents contents;
  for (const PlyHeaderElement& e : header.elements) {
    if (e.name == "face" || e.name == "tristrips") contents.faces += e.count;
    if (e.name != "vertex") continue;
    contents.vertices = e.count;
    int coordinates = 0, normals = 0;
    for (const PlyProperty& p : e.properties) {
      const bool coordinate = p.name == "x" || p.name == "y" || p.name == "z";
      const bool normal = p.name == "nx" || p.name == "ny" || p.name == "nz";
      if ((coordinate || normal) && !p.real && contents.point_problem.empty())
        contents.point_problem = fmt::format("the vertex property '{}' is not a float or double", p.name);
      coordinates += coordinate && p.real;
      normals += normal && p.real;
    }
    contents.normals = normals == 3;
    if (coordinates != 3 && contents.point_problem.empty())
      contents.point_problem = "the vertex element does not have the properties x, y and z once each";
  }
  return contents;
}

SurfaceMesh read_mesh(const fs::path& path) {
  require_mesh_extension(path);
  if (!fs::exists(path)) throw IoError(fmt::format("{}: no such file", path.string()));
  if (fs::is_directory(path)) fail(path, "is a folder, not a mesh file");
  const std::string ext = lower_extension(path);
  std::vector<Point> points;
  Polygons polygons;
  {
    const std::string text = read_all(path);
    if (text.empty()) fail(path, "empty file (0 bytes)");
    if (ext == ".off") read_off(path, text, points, polygons);
    else if (ext == ".ply") check_ply(path, text);
    else if (ext == ".stl") check_stl(path, text);
  }
  if (ext != ".off") read_with_cgal(path, ext, points, polygons);
  SurfaceMesh mesh;
  mesh.vertices.reserve(points.size());
  for (const Point& p : points) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      throw IoError(fmt::format("{}: vertex {} has a non-finite coordinate ({} {} {}); fix or remove the vertex",
                                path.string(), mesh.vertices.size(), p.x(), p.y(), p.z()));
    mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  mesh.faces.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    if (poly.size() < 3)
      throw IoError(fmt::format("{}: face {} has {} corners; a face needs at least 3",
                                path.string(), f, poly.size()));
    for (std::size_t v : poly)
      if (v >= points.size())  // a negative index in the file arrives here wrapped around
        throw IoError(fmt::format("{}: face {} refers to vertex {} but the vertices are 0..{}", path.string(), f,
                                  static_cast<std::ptrdiff_t>(v), static_cast<std::ptrdiff_t>(points.size()) - 1));
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)  // fan triangulation of polygons
      mesh.faces.push_back({static_cast<Index>(poly[0]), static_cast<Index>(poly[k]),
                            static_cast<Index>(poly[k + 1])});
  }
  if (mesh.faces.empty())
    throw IoError(fmt::format("{}: {} vertices and no faces (points only, or truncated before the first face): "
                              "medax needs a triangle surface here (`medax run` reads a file of points as a point set)",
                              path.string(), points.size()));
  return mesh;
}

void write_mesh(const fs::path& path, const SurfaceMesh& mesh) {
  require_mesh_extension(path);
  std::vector<Point> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.faces.size());
  for (const Tri& f : mesh.faces) polygons.push_back({f[0], f[1], f[2]});
  const std::string ext = lower_extension(path);
  write_file_atomic(path, [&](std::ostream& out) {
    const auto precision = CGAL::parameters::stream_precision(17);
    bool ok = false;
    if (ext == ".off") ok = CGAL::IO::write_OFF(out, points, polygons, precision);
    else if (ext == ".obj") ok = CGAL::IO::write_OBJ(out, points, polygons, precision);
    else if (ext == ".ply") ok = CGAL::IO::write_PLY(out, points, polygons, precision);
    else ok = CGAL::IO::write_STL(out, points, polygons, precision);
    if (!ok) throw IoError(fmt::format("{}: CGAL could not write the mesh", path.string()));
  });
}

}  // namespace medax
