#pragma once
// Where tests find their data, the build tree and the shared real meshes.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace medax::test {

inline std::filesystem::path data_dir() { return MEDAX_TEST_DATA_DIR; }
inline std::filesystem::path source_dir() { return MEDAX_SOURCE_DIR; }
inline std::filesystem::path binary_dir() { return MEDAX_BINARY_DIR; }
/// ../shared/data/meshes beside the repository (present on developer machines and in CI).
inline std::filesystem::path shared_meshes_dir() { return MEDAX_SHARED_MESHES_DIR; }

/// The mesh files directly in `dir` (.off, .obj, .ply, .stl), sorted; none when it is absent.
inline std::vector<std::filesystem::path> meshes_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl"))
      out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The good shared meshes (top level of ../shared/data/meshes) and the broken ones in bad/.
inline std::vector<std::filesystem::path> good_meshes() { return meshes_in(shared_meshes_dir()); }
inline std::vector<std::filesystem::path> bad_meshes() { return meshes_in(shared_meshes_dir() / "bad"); }

/// A fresh empty folder under the build tree for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = binary_dir() / "tests" / "scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace medax::test
