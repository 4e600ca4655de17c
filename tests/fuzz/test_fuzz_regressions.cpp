// Every seed and every input the fuzzers found a fault with, run through its reader: each is
// read or refused with medax's own error (IoError, PipelineError); anything else fails here.
#include "fuzz_input.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using medax::fuzz::feed;

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
