// Point-set I/O: `.xyz`/`.pts` and OFF/OBJ vertex lists read here, vertex-only PLY through CGAL's
// point reader after the mesh reader's PLY checks; the `.xyz` writer; the mesh-or-points dispatch
// of an input file; the surface-area estimate that gives every sample its area.
#include "io_text.hpp"

#include <medax/io.hpp>

#include <CGAL/IO/read_ply_points.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace medax {

namespace fs = std::filesystem;

namespace {

using detail::coordinate;
using detail::fail;
using detail::Lines;
using detail::lower_extension;
using detail::parse_integer;
using detail::read_all;
using Tokens = std::vector<std::string_view>;

constexpr const char* kNormalsHint = "drop the normal columns to have normals estimated (`normals` stage)";

bool point_set_extension(const std::string& ext) { return ext == ".xyz" || ext == ".pts"; }

/// Points and normals as a file gives them, with the line of each point (0: binary PLY).
struct RawPoints {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  std::vector<std::size_t> lines;
};

/// Three coordinates from tokens first .. first + 2 of a line.
Vec3 triple(const fs::path& path, const Tokens& t, std::size_t first, std::size_t line, std::size_t point) {
  return {coordinate(path, t[first], line, point), coordinate(path, t[first + 1], line, point),
          coordinate(path, t[first + 2], line, point)};
}

/// `.xyz` / `.pts`: every line "x y z" or every line "x y z nx ny nz"; a first line holding one
/// whole number (the point count some writers put there) is skipped.
void read_xyz(const fs::path& path, const std::string& text, RawPoints& raw) {
  Lines lines(text);
  Tokens t;
  std::size_t columns = 0;
  long long count = 0;
  while (lines.next(t)) {
    if (columns == 0 && raw.points.empty() && t.size() == 1 && parse_integer(t[0], count)) continue;
    const std::size_t i = raw.points.size();
    if (columns == 0 && t.size() != 3 && t.size() != 6)
      fail(path, fmt::format("line {}: {} values; a point line is 'x y z' or 'x y z nx ny nz'", lines.line(),
                             t.size()));
    if (columns == 0) columns = t.size();
    if (t.size() != columns)
      fail(path, fmt::format("line {}: point {} has {} values but the first point has {}: give every point 'x y z', "
                             "or every point 'x y z nx ny nz'",
                             lines.line(), i, t.size(), columns));
    raw.points.push_back(triple(path, t, 0, lines.line(), i));
    if (columns == 6) raw.normals.push_back(triple(path, t, 3, lines.line(), i));
    raw.lines.push_back(lines.line());
  }
}

/// The OFF keyword of a point set: OFF, NOFF, COFF or CNOFF (normals right after the coordinates
/// when it has an N). Returns whether the vertices carry normals.
bool off_point_keyword(const fs::path& path, const Tokens& t, std::size_t line) {
  const std::string_view keyword = t[0];
  if (keyword != "OFF" && keyword != "NOFF" && keyword != "COFF" && keyword != "CNOFF" && keyword != "NCOFF")
    fail(path, fmt::format("line {}: '{}': a point-set OFF file starts with OFF, NOFF or COFF", line, keyword));
  if (t.size() > 1 && t[1] == "BINARY")
    fail(path, fmt::format("line {}: binary OFF is not supported; write the points as ASCII OFF, PLY or .xyz", line));
  return keyword.find('N') != std::string_view::npos;
}

/// OFF (NOFF, COFF) with 0 faces: "x y z [nx ny nz] [colour]" per vertex.
void read_off_points(const fs::path& path, const std::string& text, RawPoints& raw) {
  Lines lines(text);
  Tokens t;
  if (!lines.next(t)) fail(path, "the file holds only blank lines and comments; an OFF file starts with 'OFF'");
  const bool normals = off_point_keyword(path, t, lines.line());
  std::size_t first = 1;
  if (t.size() == 1) {
    if (!lines.next(t)) fail(path, "the file ends after 'OFF'; the counts 'vertices faces edges' are missing");
    first = 0;
  }
  long long nv = 0, nf = 0;
  if (t.size() < first + 2 || !parse_integer(t[first], nv) || !parse_integer(t[first + 1], nf) || nv < 0 || nf < 0)
    fail(path, fmt::format("line {}: expected the counts 'vertices faces edges' (whole numbers >= 0)", lines.line()));
  if (nf > 0) fail(path, fmt::format("line {}: {} faces: the file is a mesh, not a point set", lines.line(), nf));
  const std::size_t needed = normals ? 6 : 3;
  for (long long v = 0; v < nv; ++v) {
    if (!lines.next(t))
      fail(path, fmt::format("the header announces {} vertices but the file ends after {} (line {}): the file is "
                             "truncated",
                             nv, v, lines.line()));
    const std::size_t i = static_cast<std::size_t>(v);
    if (t.size() < needed)
      fail(path, fmt::format("line {}: vertex {} has {} value(s); a vertex line is '{}'", lines.line(), v, t.size(),
                             normals ? "x y z nx ny nz" : "x y z"));
    raw.points.push_back(triple(path, t, 0, lines.line(), i));
    if (normals) raw.normals.push_back(triple(path, t, 3, lines.line(), i));
    raw.lines.push_back(lines.line());
  }
}

/// OBJ with `v` and optionally `vn` lines (one per `v`, in the same order); any `f` is refused.
void read_obj_points(const fs::path& path, const std::string& text, RawPoints& raw) {
  Lines lines(text);
  Tokens t;
  while (lines.next(t)) {
    const bool vertex = t[0] == "v";
    if (t[0] == "f") fail(path, fmt::format("line {}: a face: the file is a mesh, not a point set", lines.line()));
    if (!vertex && t[0] != "vn") continue;
    if (t.size() < 4)
      fail(path, fmt::format("line {}: '{}' has {} value(s); the line is '{} x y z'", lines.line(), t[0],
                             t.size() - 1, t[0]));
    std::vector<Vec3>& into = vertex ? raw.points : raw.normals;
    into.push_back(triple(path, t, 1, lines.line(), into.size()));
    if (vertex) raw.lines.push_back(lines.line());
  }
  if (!raw.normals.empty() && raw.normals.size() != raw.points.size())
    fail(path, fmt::format("{} 'vn' lines for {} 'v' lines: give one normal per point, in the same order, or none "
                           "(then they are estimated)",
                           raw.normals.size(), raw.points.size()));
}

/// PLY with a vertex element and no faces, checked as the mesh reader checks PLY, then read by CGAL.
void read_ply_points(const fs::path& path, const std::string& text, RawPoints& raw) {
  const detail::PlyContents contents = detail::check_ply_contents(path, text);
  if (contents.faces > 0)
    fail(path, fmt::format("{} faces: the file is a mesh, not a point set", contents.faces));
  if (!contents.point_problem.empty())
    fail(path, contents.point_problem + ": re-export the points with float or double x y z (and nx ny nz)");
  using Kernel = CGAL::Simple_cartesian<double>;
  using PointNormal = std::pair<Kernel::Point_3, Kernel::Vector_3>;
  std::vector<PointNormal> read;
  std::istringstream in(text, std::ios::in | std::ios::binary);
  const bool ok = CGAL::IO::read_PLY(in, std::back_inserter(read),
                                     CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointNormal>())
                                         .normal_map(CGAL::Second_of_pair_property_map<PointNormal>()));
  if (!ok || static_cast<long long>(read.size()) != contents.vertices)
    fail(path, fmt::format("cannot read the {} vertices as points (is the file complete and well formed?)",
                           contents.vertices));
  for (const auto& [p, n] : read) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      fail(path, fmt::format("vertex {} has a non-finite coordinate; fix or remove the vertex", raw.points.size()));
    raw.points.emplace_back(p.x(), p.y(), p.z());
    if (contents.normals) raw.normals.emplace_back(n.x(), n.y(), n.z());
    raw.lines.push_back(0);
  }
}

/// Where point i came from, for errors: its line when known.
std::string where(const RawPoints& raw, std::size_t i) {
  return raw.lines[i] ? fmt::format("line {}: point {}", raw.lines[i], i) : fmt::format("point {}", i);
}

/// The samples: unit normals (a zero or non-finite one is an error) and equal areas.
OrientedSamples finish(const fs::path& path, RawPoints raw) {
  if (raw.points.empty()) fail(path, "no points in the file: a point set needs at least one 'x y z' line or vertex");
  OrientedSamples samples;
  for (std::size_t i = 0; i < raw.normals.size(); ++i) {
    const double length = raw.normals[i].norm();
    if (!(length > 0) || !std::isfinite(length))
      fail(path, fmt::format("{}: the normal is zero or not finite; give a nonzero normal, or {}", where(raw, i),
                             kNormalsHint));
    raw.normals[i] /= length;
  }
  samples.points = std::move(raw.points);
  samples.normals = std::move(raw.normals);
  const double area = estimate_surface_area(samples.points);
  samples.areas.assign(samples.points.size(), area / static_cast<double>(samples.points.size()));
  return samples;
}

/// Whether an OFF text announces vertices and 0 faces (false when its header cannot be read).
bool off_without_faces(const std::string& text) {
  Lines lines(text);
  Tokens t;
  if (!lines.next(t) || t[0].size() < 3 || t[0].substr(t[0].size() - 3) != "OFF") return false;
  std::size_t first = 1;
  if (t.size() == 1) {
    if (!lines.next(t)) return false;
    first = 0;
  }
  long long nv = 0, nf = 0;
  return t.size() >= first + 2 && parse_integer(t[first], nv) && parse_integer(t[first + 1], nf) && nv > 0 && nf == 0;
}

/// Whether an OBJ text has `v` lines and no `f` line.
bool obj_without_faces(const std::string& text) {
  Lines lines(text);
  Tokens t;
  bool vertices = false;
  while (lines.next(t)) {
    if (t[0] == "f") return false;
    vertices = vertices || t[0] == "v";
  }
  return vertices;
}

}  // namespace

bool detail::holds_points_only(const fs::path& path) {
  const std::string ext = lower_extension(path);
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return false;
  const std::string text = read_all(path);
  if (ext == ".off") return off_without_faces(text);
  if (ext == ".obj") return obj_without_faces(text);
  if (ext != ".ply") return false;
  try {
    const PlyContents contents = check_ply_contents(path, text);
    return contents.vertices > 0 && contents.faces == 0;
  } catch (const IoError&) {
    return false;  // read_mesh reports it
  }
}

bool is_point_set_file(const fs::path& path) {
  return point_set_extension(lower_extension(path)) || detail::holds_points_only(path);
}

OrientedSamples read_point_set(const fs::path& path) {
  const std::string ext = lower_extension(path);
  if (!point_set_extension(ext) && ext != ".off" && ext != ".obj" && ext != ".ply")
    fail(path, fmt::format("unsupported point-set format '{}' (use .xyz, .pts, or .ply, .off, .obj without faces)",
                           ext));
  if (!fs::exists(path)) fail(path, "no such file");
  if (fs::is_directory(path)) fail(path, "is a folder, not a point-set file");
  const std::string text = read_all(path);
  if (text.empty()) fail(path, "empty file (0 bytes)");
  RawPoints raw;
  if (point_set_extension(ext)) read_xyz(path, text, raw);
  else if (ext == ".off") read_off_points(path, text, raw);
  else if (ext == ".obj") read_obj_points(path, text, raw);
  else read_ply_points(path, text, raw);
  return finish(path, std::move(raw));
}

void write_point_set(const fs::path& path, const OrientedSamples& samples) {
  const bool normals = samples.normals.size() == samples.size();
  write_file_atomic(path, [&](std::ostream& out) {
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Vec3& p = samples.points[i];
      out << fmt::format("{:.17g} {:.17g} {:.17g}", p.x(), p.y(), p.z());
      if (normals) out << fmt::format(" {:.17g} {:.17g} {:.17g}", samples.normals[i].x(), samples.normals[i].y(),
                                      samples.normals[i].z());
      out << '\n';
    }
  });
}

Shape read_shape(const fs::path& path) {
  Shape shape;
  if (is_point_set_file(path)) shape.samples = read_point_set(path);
  else shape.mesh = read_mesh(path);
  shape.source = path.string();
  return shape;
}

double estimate_surface_area(const std::vector<Vec3>& points) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Traits = CGAL::Search_traits_3<Kernel>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  constexpr std::size_t kWanted = 8;
  if (points.size() < 3) return 0;
  const std::size_t k = std::min(kWanted, points.size() - 1);
  std::vector<Kernel::Point_3> cgal;
  cgal.reserve(points.size());
  for (const Vec3& p : points) cgal.emplace_back(p.x(), p.y(), p.z());
  const Search::Tree tree(cgal.begin(), cgal.end());
  // A fixed stride of query points bounds the cost on large clouds and keeps the result deterministic.
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 20000);
  std::vector<double> area_per_point;
  for (std::size_t i = 0; i < cgal.size(); i += stride) {
    const Search search(tree, cgal[i], static_cast<unsigned>(k + 1));  // the point itself comes first
    double squared = 0;
    for (const auto& neighbour : search) squared = std::max(squared, neighbour.second);
    area_per_point.push_back(M_PI * squared / static_cast<double>(k - 1));
  }
  auto middle = area_per_point.begin() + static_cast<std::ptrdiff_t>(area_per_point.size() / 2);
  std::nth_element(area_per_point.begin(), middle, area_per_point.end());
  return *middle * static_cast<double>(points.size());
}

}  // namespace medax
