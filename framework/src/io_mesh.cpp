// Surface mesh I/O through CGAL's polygon-soup readers and writers (OFF, OBJ, PLY, STL).
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

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void require_mesh_extension(const fs::path& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
    throw IoError(fmt::format("{}: unsupported mesh format '{}' (use .off, .obj, .ply or .stl)",
                              path.string(), ext));
}

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw IoError(fmt::format("{}: {}", path.string(), what));
}

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file (check its permissions)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Lines of a text split into whitespace-separated tokens, '#' comments removed, with line numbers.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  /// Next line with at least one token; false at the end of the text.
  bool next(std::vector<std::string_view>& tokens) {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      line = line.substr(0, line.find('#'));
      tokens.clear();
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        const std::size_t b = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i > b) tokens.push_back(line.substr(b, i - b));
      }
      if (!tokens.empty()) return true;
    }
    return false;
  }
  std::size_t line() const { return line_; }
  std::size_t offset() const { return std::min(pos_, text_.size()); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

bool parse_integer(std::string_view token, long long& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

/// Parses a coordinate; the error names the element and the line.
double coordinate(const fs::path& path, std::string_view token, const Lines& lines, std::size_t vertex) {
  const std::string s(token);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size())
    fail(path, fmt::format("line {}: vertex {}: '{}' is not a number", lines.line(), vertex, s));
  if (!std::isfinite(v))
    fail(path, fmt::format("line {}: vertex {} has the non-finite coordinate '{}' (fix or remove the vertex)",
                           lines.line(), vertex, s));
  return v;
}

/// A declared element count that the file cannot hold: refused before anything is allocated.
void check_counts_fit(const fs::path& path, const std::string& announced, long double needed, std::uintmax_t bytes) {
  if (needed > static_cast<long double>(bytes))
    fail(path, fmt::format("the header announces {} but the file has only {} bytes after it (at least {:.0f} "
                           "needed): the file is truncated or its header is wrong; re-export the mesh",
                           announced, bytes, static_cast<double>(needed)));
}

/// ASCII OFF ("OFF" keyword or none) checked in full before CGAL reads it: header counts against
/// the file size, then every vertex (3 finite coordinates) and face (corner count, indices in range)
/// with its line. Variants (COFF, NOFF, 4OFF, binary ...) are left to CGAL after the size check.
void check_off(const fs::path& path, const std::string& text) {
  Lines lines(text);
  std::vector<std::string_view> t;
  if (!lines.next(t)) fail(path, "the file holds only blank lines and comments; an OFF file starts with 'OFF'");
  std::size_t first = 0;
  bool plain = true;  // "OFF" or no keyword: checked line by line below
  if (t[0].size() >= 3 && t[0].substr(t[0].size() - 3) == "OFF") {
    const std::string_view keyword = t[0];
    plain = keyword == "OFF";
    // nOFF has a dimension line and binary OFF binary counts: left to CGAL's scanner.
    if (keyword.find('n') != std::string_view::npos || (t.size() > 1 && t[1] == "BINARY")) return;
    first = 1;
    if (t.size() == 1) {
      if (!lines.next(t)) fail(path, "the file ends after 'OFF'; the counts 'vertices faces edges' are missing");
      first = 0;
    }
  }
  long long nv = 0, nf = 0;
  if (t.size() < first + 2 || !parse_integer(t[first], nv) || !parse_integer(t[first + 1], nf) || nv < 0 || nf < 0)
    fail(path, fmt::format("line {}: expected the counts 'vertices faces edges' (whole numbers >= 0)", lines.line()));
  const std::uintmax_t rest = text.size() - lines.offset();
  // A vertex line takes at least 6 bytes ("0 0 0\n"), a face line 8 ("3 0 1 2\n"); binary takes more.
  check_counts_fit(path, fmt::format("{} vertices and {} faces", nv, nf),
                   6.0L * nv + 8.0L * nf - 1, rest);
  if (!plain) return;
  for (long long v = 0; v < nv; ++v) {
    if (!lines.next(t))
      fail(path, fmt::format("the header announces {} vertices but the file ends after {} (line {}): "
                             "the file is truncated",
                             nv, v, lines.line()));
    if (t.size() < 3)
      fail(path, fmt::format("line {}: vertex {} has {} coordinate(s); a vertex line is 'x y z'", lines.line(), v,
                             t.size()));
    for (int k = 0; k < 3; ++k) coordinate(path, t[k], lines, static_cast<std::size_t>(v));
  }
  for (long long f = 0; f < nf; ++f) {
    if (!lines.next(t))
      fail(path, fmt::format("the header announces {} faces but the file ends after {} (line {}): "
                             "the file is truncated",
                             nf, f, lines.line()));
    long long n = 0;
    if (!parse_integer(t[0], n) || n < 0)
      fail(path, fmt::format("line {}: face {}: '{}' is not a corner count", lines.line(), f, t[0]));
    if (static_cast<long long>(t.size()) - 1 < n)
      fail(path, fmt::format("line {}: face {} announces {} corners but lists only {}", lines.line(), f, n,
                             t.size() - 1));
    if (n < 3) fail(path, fmt::format("line {}: face {} has {} corners; a face needs at least 3", lines.line(), f, n));
    for (long long k = 1; k <= n; ++k) {
      long long index = 0;
      if (!parse_integer(t[k], index))
        fail(path, fmt::format("line {}: face {}: '{}' is not a vertex index", lines.line(), f, t[k]));
      if (index < 0 || index >= nv)
        fail(path, fmt::format("line {}: face {} refers to vertex {} but the vertices are 0..{}", lines.line(), f,
                               index, nv - 1));
    }
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
      for (int k = 1; k <= 3; ++k) coordinate(path, t[k], lines, static_cast<std::size_t>(nv));
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
      for (int k = 1; k <= 3; ++k) coordinate(path, t[k], lines, vertex);
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

/// PLY header: element counts against the bytes after the header (ASCII: 2 bytes per property at
/// least; binary: the property sizes, a list its count).
void check_ply(const fs::path& path, const std::string& text) {
  const std::size_t end = text.find("end_header");
  if (text.rfind("ply", 0) != 0 || end == std::string::npos)
    fail(path, "not a PLY file: it must start with 'ply' and have an 'end_header' line");
  const std::size_t body = std::min(text.size(), text.find('\n', end) == std::string::npos ? text.size()
                                                                                           : text.find('\n', end) + 1);
  Lines lines(std::string_view(text).substr(0, end));
  std::vector<std::string_view> t;
  bool ascii = false;
  struct Element { std::string name; long long count; long double bytes; };
  std::vector<Element> elements;
  const auto size_of = [](std::string_view type) -> int {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "double" || type == "float64") return 8;
    return 4;
  };
  while (lines.next(t)) {
    if (t[0] == "format" && t.size() > 1) ascii = t[1] == "ascii";
    if (t[0] == "element") {
      long long n = 0;
      if (t.size() != 3 || !parse_integer(t[2], n) || n < 0)
        fail(path, fmt::format("line {}: an element line is 'element NAME COUNT'", lines.line()));
      elements.push_back({std::string(t[1]), n, 0});
    } else if (t[0] == "property" && !elements.empty() && t.size() >= 3) {
      elements.back().bytes += ascii ? 2 : (t[1] == "list" && t.size() >= 5 ? size_of(t[2]) : size_of(t[1]));
    }
  }
  long double needed = 0;
  std::string announced;
  for (const Element& e : elements) {
    needed += static_cast<long double>(e.count) * std::max<long double>(e.bytes, 1);
    announced += fmt::format("{}{} '{}' elements", announced.empty() ? "" : ", ", e.count, e.name);
  }
  check_counts_fit(path, announced, needed - 1, text.size() - body);
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

}  // namespace

SurfaceMesh read_mesh(const fs::path& path) {
  require_mesh_extension(path);
  if (!fs::exists(path)) throw IoError(fmt::format("{}: no such file", path.string()));
  if (fs::is_directory(path)) fail(path, "is a folder, not a mesh file");
  const std::string ext = lower_extension(path);
  {
    const std::string text = read_all(path);
    if (text.empty()) fail(path, "empty file (0 bytes)");
    if (ext == ".off") check_off(path, text);
    else if (ext == ".ply") check_ply(path, text);
    else if (ext == ".stl") check_stl(path, text);
  }
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
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
                              "medax needs a triangle surface",
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
