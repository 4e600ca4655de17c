// write_file_atomic: the target appears complete or not at all, and no temporary file remains.
#include "kernel_test_support.hpp"

#include <medax/io.hpp>

#include <ostream>

using namespace medax;
using medax::test::read_text;
using medax::test::scratch_dir;

namespace fs = std::filesystem;

namespace {
std::vector<std::string> folder_contents(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void write_half_then_throw(std::ostream& out) {
  out << "first half of the data\n";
  throw std::runtime_error("failed half-way");
}
}  // namespace

TEST_CASE("write_file_atomic writes the whole body to the target", "[io][atomic]") {
  const auto dir = scratch_dir("atomic_ok");
  write_file_atomic(dir / "out.txt", [](std::ostream& out) { out << "complete\n"; });
  CHECK(read_text(dir / "out.txt") == "complete\n");
  CHECK(folder_contents(dir) == std::vector<std::string>{"out.txt"});
  // Replacing an existing file.
  write_file_atomic(dir / "out.txt", [](std::ostream& out) { out << "replaced\n"; });
  CHECK(read_text(dir / "out.txt") == "replaced\n");
  CHECK(folder_contents(dir) == std::vector<std::string>{"out.txt"});
}

TEST_CASE("a body that throws leaves neither the target nor a temporary file", "[io][atomic]") {
  const auto dir = scratch_dir("atomic_throw");
  CHECK_THROWS_WITH(write_file_atomic(dir / "out.txt", write_half_then_throw), "failed half-way");
  CHECK(folder_contents(dir).empty());
}

TEST_CASE("a body that throws leaves an existing target untouched", "[io][atomic]") {
  const auto dir = scratch_dir("atomic_keep");
  medax::test::write_text(dir / "out.txt", "the old contents\n");
  CHECK_THROWS(write_file_atomic(dir / "out.txt", write_half_then_throw));
  CHECK(read_text(dir / "out.txt") == "the old contents\n");
  CHECK(folder_contents(dir) == std::vector<std::string>{"out.txt"});
}

TEST_CASE("writing into a missing folder is an IoError naming the file", "[io][atomic]") {
  const auto dir = scratch_dir("atomic_missing_dir");
  CHECK_THROWS_MATCHES(write_file_atomic(dir / "no" / "out.txt", [](std::ostream& out) { out << "x"; }), IoError,
                       Catch::Matchers::Predicate<IoError>([](const IoError& e) {
                         return std::string(e.what()).find("out.txt") != std::string::npos;
                       }));
  CHECK_FALSE(fs::exists(dir / "no"));
}
