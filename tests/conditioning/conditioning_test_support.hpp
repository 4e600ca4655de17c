#pragma once
// Helpers for the conditioning tests: the real meshes' facts (datasets/meshcheck.jsonl), small
// hand-made broken meshes, and a registry holding the conditioning plugin.
#include <test_paths.hpp>

#include <medax/io.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/stage.hpp>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace medax::test {

/// datasets/meshcheck.jsonl (the team's independent checker on the shared set): the "meshcheck"
/// object of every file, by its name in datasets/meshes.tsv.
inline const std::map<std::string, nlohmann::json>& manifest_checks() {
  static const std::map<std::string, nlohmann::json> checks = [] {
    std::map<std::string, nlohmann::json> out;
    std::ifstream in(source_dir() / "datasets" / "meshcheck.jsonl");
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      const auto j = nlohmann::json::parse(line);
      out[j.at("file").get<std::string>()] = j.at("meshcheck");
    }
    return out;
  }();
  return checks;
}

/// A mesh's name in the manifest ("cow.off" -> "bad/cow.off" when in a bad/ folder).
inline std::string manifest_key(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  return path.parent_path().filename() == "bad" ? "bad/" + name : name;
}

/// A regular tetrahedron-like solid: 4 vertices, 4 outward faces.
inline SurfaceMesh tetrahedron(const Vec3& offset = Vec3::Zero(), double scale = 1.0) {
  SurfaceMesh m;
  m.vertices = {offset + scale * Vec3(0, 0, 0), offset + scale * Vec3(1, 0, 0), offset + scale * Vec3(0, 1, 0),
                offset + scale * Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

/// Both meshes in one (vertex indices of `b` shifted).
inline SurfaceMesh merged(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh m = a;
  const auto shift = static_cast<Index>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Tri f : b.faces) m.faces.push_back({f[0] + shift, f[1] + shift, f[2] + shift});
  return m;
}

inline SurfaceMesh reversed(SurfaceMesh m) {
  for (Tri& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

/// Every face gets its own three vertices (a polygon soup with all vertices duplicated).
inline SurfaceMesh exploded(const SurfaceMesh& in) {
  SurfaceMesh m;
  for (const Tri& f : in.faces) {
    const auto base = static_cast<Index>(m.vertices.size());
    for (Index v : f) m.vertices.push_back(in.vertices[v]);
    m.faces.push_back({base, base + 1, base + 2});
  }
  return m;
}

/// The same face up to a rotation of its corners (same orientation).
inline bool same_oriented_face(const Tri& a, const Tri& b) {
  for (int r = 0; r < 3; ++r)
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
  return false;
}

inline double bbox_diag(const SurfaceMesh& m) { return bbox_diagonal(m.vertices); }

/// A registry holding only the conditioning plugin (shared; tests must not modify it).
inline const Registry& conditioning_registry() {
  static Registry* registry = [] {
    auto* r = new Registry();
    r->load_file(MEDAX_CONDITIONING_PLUGIN);
    return r;
  }();
  return *registry;
}

/// A stage of the conditioning plugin: at its defaults (a fresh stage is), with `settings` applied.
inline std::unique_ptr<Stage> make_stage(const std::string& name, const std::map<std::string, ParamValue>& settings = {}) {
  const Registry& registry = conditioning_registry();
  REQUIRE(registry.find(name) != nullptr);
  auto stage = registry.create(name);
  const std::vector<ParamSpec> specs = stage->param_specs();
  ParamSet params;
  for (const auto& [key, value] : settings) {
    INFO("parameter " << key);
    REQUIRE(std::any_of(specs.begin(), specs.end(), [&key = key](const ParamSpec& p) { return p.name == key; }));
    params.set(key, value);
  }
  stage->configure(params);
  stage->set_id(name);
  return stage;
}

/// A context that keeps what the stage logs.
class RecordingContext : public BasicContext {
 public:
  explicit RecordingContext(std::uint64_t seed = 0) : BasicContext(seed) {}
  void info(std::string_view message) override { infos.emplace_back(message); }
  void warn(std::string_view message) override { warnings.emplace_back(message); }
  bool logged(const std::string& text) const {
    for (const auto* list : {&infos, &warnings})
      for (const auto& line : *list)
        if (line.find(text) != std::string::npos) return true;
    return false;
  }
  std::vector<std::string> infos, warnings;
};

/// Runs `stage` (prepare, then run) on a scene holding `shape`; returns the scene.
inline Scene run_stage(Stage& stage, Shape shape, Context& ctx) {
  Scene scene;
  scene.shape = std::move(shape);
  stage.prepare(scene);
  stage.run(scene, ctx);
  return scene;
}

inline Shape shape_of(const std::filesystem::path& path) {
  Shape s;
  s.mesh = read_mesh(path);
  s.source = path.string();
  return s;
}

}  // namespace medax::test
