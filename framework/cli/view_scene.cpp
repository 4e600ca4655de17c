#include "view_scene.hpp"

#include "view_ply.hpp"

#include <medax/io.hpp>
#include <medax/services/closest_point.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <stdexcept>
#include <unordered_set>

namespace medax::cli {

namespace fs = std::filesystem;

namespace {

const std::set<std::string> kGeometryColumns{"x", "y", "z", "radius", "vertex1", "vertex2"};

std::vector<float> as_floats(const std::vector<double>& values) {
  std::vector<float> out(values.size());
  std::transform(values.begin(), values.end(), out.begin(), [](double v) {
    return std::isfinite(v) ? static_cast<float>(v) : std::numeric_limits<float>::quiet_NaN();
  });
  return out;
}

void append(std::vector<float>& out, const Vec3& p) {
  out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z())});
}

void append(std::vector<std::uint32_t>& out, const Tri& f) {
  out.insert(out.end(), {std::uint32_t(f[0]), std::uint32_t(f[1]), std::uint32_t(f[2])});
}

const std::vector<double>& column(const PlyTable& table, const std::string& name, const fs::path& file) {
  const PlyProperty* p = table.find(name);
  if (!p)
    throw std::runtime_error(fmt::format("{}: element '{}' has no '{}' property", file.string(), table.name, name));
  return p->values;
}

/// The x, y, z columns of `table` as points, x y z each.
std::vector<float> points(const PlyTable& table, const fs::path& file) {
  const auto &x = column(table, "x", file), &y = column(table, "y", file), &z = column(table, "z", file);
  std::vector<float> out;
  out.reserve(3 * table.rows);
  for (std::size_t i = 0; i < table.rows; ++i) append(out, Vec3(x[i], y[i], z[i]));
  return out;
}

/// Edges bounding no triangle, as vertex pairs, and their rows in the edge list.
void keep_curves(const std::vector<std::uint32_t>& edges, ViewScene& scene, std::vector<std::size_t>& rows) {
  const auto key = [](std::uint64_t a, std::uint64_t b) { return a < b ? a << 32 | b : b << 32 | a; };
  std::unordered_set<std::uint64_t> in_triangle;
  const auto& t = scene.triangles;
  for (std::size_t k = 0; k + 2 < t.size(); k += 3)
    for (int c = 0; c < 3; ++c) in_triangle.insert(key(t[k + c], t[k + (c + 1) % 3]));
  for (std::size_t e = 0; 2 * e + 1 < edges.size(); ++e) {
    if (in_triangle.count(key(edges[2 * e], edges[2 * e + 1]))) continue;
    scene.curves.insert(scene.curves.end(), {edges[2 * e], edges[2 * e + 1]});
    rows.push_back(e);
  }
}

/// Every property of `table` but the geometry as a field of `element`, taken at `rows`.
void add_fields(const PlyTable& table, const std::string& element, const std::vector<std::size_t>& rows,
                ViewScene& scene) {
  for (const PlyProperty& p : table.properties) {
    if (kGeometryColumns.count(p.name) && p.name != "radius") continue;
    ViewField field{p.name, element, p.integer, {}};
    field.values.reserve(rows.size());
    for (std::size_t row : rows) field.values.push_back(static_cast<float>(p.values[row]));
    scene.fields.push_back(std::move(field));
  }
}

std::vector<std::size_t> all_rows(std::size_t count) {
  std::vector<std::size_t> rows(count);
  for (std::size_t i = 0; i < count; ++i) rows[i] = i;
  return rows;
}

void read_medial_ply(const fs::path& file, ViewScene& scene) {
  const auto tables = read_ply_tables(file);
  const auto vertex = tables.find("vertex");
  if (vertex == tables.end()) throw std::runtime_error(fmt::format("{}: no vertex element", file.string()));
  const PlyTable& v = vertex->second;
  scene.positions = points(v, file);
  scene.radii = as_floats(column(v, "radius", file));
  add_fields(v, "vertex", all_rows(v.rows), scene);
  if (const auto face = tables.find("face"); face != tables.end()) {
    scene.triangles = face->second.triangles;
    add_fields(face->second, "face", face->second.triangle_row, scene);
  }
  if (const auto edge = tables.find("edge"); edge != tables.end()) {
    const PlyTable& e = edge->second;
    const auto &a = column(e, "vertex1", file), &b = column(e, "vertex2", file);
    std::vector<std::uint32_t> pairs;
    for (std::size_t i = 0; i < e.rows; ++i) pairs.insert(pairs.end(), {std::uint32_t(a[i]), std::uint32_t(b[i])});
    std::vector<std::size_t> rows;
    keep_curves(pairs, scene, rows);
    add_fields(e, "edge", rows, scene);
  }
}

void read_medial_ma(const fs::path& file, ViewScene& scene) {
  const MedialComplex mc = read_ma(file);
  for (const Vec3& c : mc.centres) append(scene.positions, c);
  scene.radii = as_floats(mc.radii);
  scene.fields.push_back({"radius", "vertex", false, scene.radii});
  for (const Tri& f : mc.faces) append(scene.triangles, f);
  std::vector<std::uint32_t> pairs;
  for (const Segment& e : mc.edges) pairs.insert(pairs.end(), {std::uint32_t(e[0]), std::uint32_t(e[1])});
  std::vector<std::size_t> rows;
  keep_curves(pairs, scene, rows);
}

void check_indices(const ViewScene& scene, const fs::path& file) {
  const std::size_t n = scene.radii.size();
  for (const auto* list : {&scene.triangles, &scene.curves})
    for (std::uint32_t i : *list)
      if (i >= n) throw std::runtime_error(fmt::format("{}: vertex index {} is not in 0..{}", file.string(), i, n - 1));
}

ViewSurface surface_layer(std::string id, std::string name, const SurfaceMesh& mesh) {
  ViewSurface s;
  s.id = std::move(id);
  s.name = std::move(name);
  for (const Vec3& p : mesh.vertices) append(s.positions, p);
  for (const Tri& f : mesh.faces) append(s.triangles, f);
  return s;
}

const std::set<std::string> kNotAField{"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "alpha"};

/// What a stage's PLY layer is coloured by: its vertex `distance` (the reconstruction envelope's
/// distance to the surface), else its first face property (MSD's primitive), else its first
/// vertex property; none when it has its own colours.
ViewField layer_field(const PlyTable& vertex, const PlyTable* face, const std::vector<std::size_t>& face_rows) {
  if (vertex.find("red")) return {};
  if (const PlyProperty* d = vertex.find("distance")) return {d->name, "vertex", false, as_floats(d->values)};
  const auto first = [](const PlyTable& t) -> const PlyProperty* {
    for (const PlyProperty& p : t.properties)
      if (!kNotAField.count(p.name)) return &p;
    return nullptr;
  };
  if (const PlyProperty* p = face ? first(*face) : nullptr) {
    ViewField f{p->name, "face", p->integer, {}};
    for (std::size_t row : face_rows) f.values.push_back(static_cast<float>(p->values[row]));
    return f;
  }
  if (const PlyProperty* p = first(vertex)) return {p->name, "vertex", p->integer, as_floats(p->values)};
  return {};
}

/// A PLY a stage wrote: a surface (e.g. durix_segmentation.ply, with its vertex colours; MSD's
/// primitives) or a point set (the reconstruction's envelope samples).
ViewSurface ply_surface(const fs::path& file) {
  const auto tables = read_ply_tables(file);
  const auto vertex = tables.find("vertex"), face = tables.find("face");
  if (vertex == tables.end() || vertex->second.rows == 0) throw std::runtime_error("it has no vertices");
  const PlyTable& v = vertex->second;
  const PlyTable* f = face == tables.end() ? nullptr : &face->second;
  ViewSurface s;
  s.id = s.name = file.filename().string();
  s.positions = points(v, file);
  if (f) s.triangles = f->triangles;
  for (std::uint32_t i : s.triangles)
    if (i >= v.rows) throw std::runtime_error(fmt::format("vertex index {} is not in 0..{}", i, v.rows - 1));
  const PlyProperty *r = v.find("red"), *g = v.find("green"), *b = v.find("blue");
  if (r && g && b)
    for (std::size_t i = 0; i < v.rows; ++i)
      s.colours.insert(s.colours.end(),
                       {std::uint8_t(r->values[i]), std::uint8_t(g->values[i]), std::uint8_t(b->values[i])});
  s.field = layer_field(v, f, f ? f->triangle_row : std::vector<std::size_t>{});
  if (!s.field.name.empty()) s.opacity = 1;  // a coloured layer is looked at, not through
  return s;
}

/// The input mesh named by config.resolved.yaml's top-level `input:` (medax writes it on one
/// line, unquoted or double-quoted), or empty.
fs::path input_mesh(const fs::path& folder) {
  std::ifstream in(folder / "config.resolved.yaml");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("input:", 0) != 0) continue;
    std::string value = line.substr(6);
    value.erase(0, value.find_first_not_of(" \t"));
    value.erase(value.find_last_not_of(" \t\r") + 1);
    if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'')) value = value.substr(1, value.size() - 2);
    return value;
  }
  return {};
}

/// Adds the input as a layer; returns its mesh (empty for a point cloud or an unreadable input).
SurfaceMesh add_input_surface(const fs::path& folder, ViewScene& scene) {
  const fs::path input = input_mesh(folder);
  if (input.empty()) {
    scene.notes.push_back(fmt::format("{} names no input mesh: the page shows no input surface",
                                      (folder / "config.resolved.yaml").string()));
    return {};
  }
  try {
    Shape shape = read_shape(input);
    const bool cloud = shape.mesh.empty();  // a point-set input: its points, as a point layer
    if (cloud) shape.mesh.vertices = std::move(shape.samples.points);
    ViewSurface s = surface_layer("surface", cloud ? "input point cloud" : "input surface", shape.mesh);
    s.visible = true;
    scene.surfaces.push_back(std::move(s));
    return cloud ? SurfaceMesh{} : shape.mesh;
  } catch (const std::exception& e) {
    scene.notes.push_back(fmt::format("the input surface is not shown: {}", e.what()));
    return {};
  }
}

/// The reconstruction's layer, coloured by each vertex's distance to the input surface (when
/// there is one) in the input's units.
void show_as_reconstruction(ViewSurface& s, const std::string& name, const SurfaceMesh& input) {
  s.id = "reconstruction";
  s.name = "reconstruction (" + name + ")";
  s.colour = "#e8903a";
  s.opacity = 0.35;
  s.visible = true;
  if (input.empty() || s.positions.empty()) return;
  std::vector<Vec3> vertices;
  for (std::size_t i = 0; i + 2 < s.positions.size(); i += 3)
    vertices.emplace_back(s.positions[i], s.positions[i + 1], s.positions[i + 2]);
  s.field = {"distance to the input surface", "vertex", false,
             as_floats(services::SurfaceDistance(input).distances(vertices))};
  s.opacity = 1;  // a coloured layer is looked at, not through
}

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

/// The reconstruction (<id>_reconstruction.off) and every other surface file of the folder.
void add_stage_surfaces(const fs::path& folder, const fs::path& medial_file, const SurfaceMesh& input,
                        ViewScene& scene) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    const std::string ext = file.extension().string(), name = file.filename().string();
    if (file == medial_file || file.stem() == "medial" || (ext != ".ply" && ext != ".off" && ext != ".obj")) continue;
    try {
      ViewSurface s = ext == ".ply" ? ply_surface(file) : surface_layer(name, name, read_mesh(file));
      if (ends_with(file.stem().string(), "reconstruction")) show_as_reconstruction(s, name, input);
      scene.surfaces.push_back(std::move(s));
    } catch (const std::exception& e) {
      scene.notes.push_back(fmt::format("{} is not shown: {}", name, e.what()));
    }
  }
}

std::string run_title(const fs::path& folder, ViewScene& scene) {
  std::ifstream in(folder / "run.json");
  const nlohmann::json run = nlohmann::json::parse(in, nullptr, false);
  std::string title = folder.filename().string();
  if (run.is_discarded() || !run.is_object()) {
    scene.notes.push_back(fmt::format("{} has no readable run.json: it may be an unfinished run", folder.string()));
    return title;
  }
  if (run.value("status", "") != "ok")
    scene.notes.push_back(fmt::format("the run did not finish ('{}'); the page shows what it wrote",
                                      run.value("status", std::string("unknown"))));
  return run.value("pipeline", std::string("run")) + ": " + title;
}

}  // namespace

ViewScene read_view_scene(const fs::path& run_folder) {
  const fs::path folder = fs::absolute(run_folder).lexically_normal();
  if (!fs::is_directory(folder))
    throw std::runtime_error(
        fmt::format("{} is not a folder; give a run folder (what `medax run` printed after "
                    "'results:')",
                    run_folder.string()));
  ViewScene scene;
  fs::path medial_file = folder / "medial.ply";
  if (!fs::exists(medial_file)) medial_file = folder / "medial.ma";
  if (!fs::exists(medial_file))
    throw std::runtime_error(
        fmt::format("{} holds no medial.ply or medial.ma: give a run folder whose pipeline "
                    "writes `outputs: medial: [ply]`",
                    run_folder.string()));
  scene.title = run_title(folder, scene);
  if (medial_file.extension() == ".ply")
    read_medial_ply(medial_file, scene);
  else
    read_medial_ma(medial_file, scene);
  check_indices(scene, medial_file);
  const SurfaceMesh input = add_input_surface(folder, scene);
  add_stage_surfaces(folder, medial_file, input, scene);
  return scene;
}

}  // namespace medax::cli
