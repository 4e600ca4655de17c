#pragma once
// Where tests find their data: the bundled meshes (tests/data), the build tree and the mesh
// corpus of datasets/meshes.tsv that scripts/fetch-meshes.sh puts in data/meshes.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace medax::test {

/// tests/data: the small meshes the tests need, bundled (licences in its README.md).
inline std::filesystem::path data_dir() { return MEDAX_TEST_DATA_DIR; }
inline std::filesystem::path source_dir() { return MEDAX_SOURCE_DIR; }
inline std::filesystem::path binary_dir() { return MEDAX_BINARY_DIR; }

/// The mesh corpus folder: $MEDAX_DATA_DIR when set, else <repo>/data/meshes (as for
/// scripts/fetch-meshes.sh, which fills it; scripts/install-deps.sh adds the Debian part).
inline std::filesystem::path corpus_dir() {
  const char* dir = std::getenv("MEDAX_DATA_DIR");
  return dir && *dir ? std::filesystem::path(dir) : source_dir() / "data" / "meshes";
}

/// A mesh of the corpus by its name in datasets/meshes.tsv ("armadillo.off", "bad/cow.off").
/// Throws (failing the test, never skipping it) when the file is not there.
inline std::filesystem::path corpus_mesh(const std::string& name) {
  const auto path = corpus_dir() / name;
  if (!std::filesystem::is_regular_file(path))
    throw std::runtime_error("mesh " + name + " is not in the corpus folder " + corpus_dir().string() +
                             ": run scripts/fetch-meshes.sh (--debian for the CGAL meshes, offline; "
                             "--network for the others)");
  return path;
}

/// A row of datasets/meshes.tsv (the columns the tests use).
struct CorpusEntry {
  std::string name, category, source;
  bool from_debian() const { return source.rfind("debian:", 0) == 0; }
};

inline std::vector<CorpusEntry> corpus_manifest() {
  const auto path = source_dir() / "datasets" / "meshes.tsv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the mesh manifest " + path.string());
  std::vector<CorpusEntry> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("name\t", 0) == 0) continue;
    std::istringstream row(line);
    CorpusEntry e;
    std::getline(row, e.name, '\t');
    std::getline(row, e.category, '\t');
    std::getline(row, e.source, '\t');
    out.push_back(e);
  }
  return out;
}

/// The Debian corpus (the manifest's meshes from libcgal-demo, which CI and install-deps.sh
/// fetch offline): its good meshes of the shared set, or its broken ones (category "bad").
/// Each must be present (corpus_mesh); sorted by name.
inline std::vector<std::filesystem::path> debian_corpus(bool broken) {
  std::vector<std::filesystem::path> out;
  for (const CorpusEntry& e : corpus_manifest())
    if (e.from_debian() && e.category != "extra" && (e.category == "bad") == broken) out.push_back(corpus_mesh(e.name));
  std::sort(out.begin(), out.end());
  return out;
}

/// A fresh empty folder under the build tree for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = binary_dir() / "tests" / "scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace medax::test
