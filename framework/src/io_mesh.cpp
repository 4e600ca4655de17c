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

}  // namespace

SurfaceMesh read_mesh(const fs::path& path) {
  require_mesh_extension(path);
  if (!fs::exists(path)) throw IoError(fmt::format("{}: no such file", path.string()));
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path.string(), points, polygons, CGAL::parameters::verbose(false)))
    throw IoError(fmt::format("{}: cannot parse as {} (is the file complete and well formed?)",
                              path.string(), lower_extension(path).substr(1)));
  SurfaceMesh mesh;
  mesh.vertices.reserve(points.size());
  for (const Point& p : points) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      throw IoError(fmt::format("{}: vertex {} has a non-finite coordinate", path.string(),
                                mesh.vertices.size()));
    mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  mesh.faces.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    if (poly.size() < 3)
      throw IoError(fmt::format("{}: face {} has {} corners; a face needs at least 3",
                                path.string(), f, poly.size()));
    for (std::size_t v : poly)
      if (v >= points.size())
        throw IoError(fmt::format("{}: face {} refers to vertex {} but there are only {}",
                                  path.string(), f, v, points.size()));
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)  // fan triangulation of polygons
      mesh.faces.push_back({static_cast<Index>(poly[0]), static_cast<Index>(poly[k]),
                            static_cast<Index>(poly[k + 1])});
  }
  if (mesh.faces.empty()) throw IoError(fmt::format("{}: the mesh has no faces", path.string()));
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
