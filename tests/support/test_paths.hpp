#pragma once
// Where tests find their data, the build tree and the shared real meshes.
#include <filesystem>

namespace medax::test {

inline std::filesystem::path data_dir() { return MEDAX_TEST_DATA_DIR; }
inline std::filesystem::path source_dir() { return MEDAX_SOURCE_DIR; }
inline std::filesystem::path binary_dir() { return MEDAX_BINARY_DIR; }
/// ../shared/data/meshes beside the repository (present on developer machines and in CI).
inline std::filesystem::path shared_meshes_dir() { return MEDAX_SHARED_MESHES_DIR; }

/// A fresh empty folder under the build tree for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = binary_dir() / "tests" / "scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace medax::test
