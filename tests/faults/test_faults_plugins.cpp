// Broken files on the plugin path (issue 13): a truncated .so (cut at many points), a zero-byte
// .so, a text file named .so, a foreign ELF (an executable), a plugin of another ABI. Each is
// named in a clear error by `medax plugins`, which exits 2 without crashing; the good plugin
// beside it still lists, validates and runs.
#include "fault_helpers.hpp"

using namespace medax::test;
namespace fs = std::filesystem;

namespace {

const fs::path kGoodSo = plugin_dir("good") / "libmedax_kernel_test_good.so";

/// A plugin folder with the good plugin and `bad` (written by `make`) as libbroken.so.
fs::path folder_with(const fs::path& dir, const std::string& name, const std::string& bytes) {
  const fs::path folder = dir / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  fs::copy_file(kGoodSo, folder / kGoodSo.filename());
  write_text(folder / "libbroken.so", bytes);
  return folder;
}

/// `medax plugins` names the broken file with `reason`; the good plugin lists, validates, runs.
void check_isolated(const fs::path& folder, const std::string& broken, const std::string& reason, const fs::path& dir) {
  const auto listed = run_medax("plugins", folder.string(), dir);
  INFO(listed.err);
  CHECK(listed.code == 2);
  CHECK_THAT(listed.err, Catch::Contains("error: plugin " + (folder / broken).string() + ": " + reason));
  CHECK_THAT(listed.out, Catch::Contains("test_centroid"));
  const auto file = write_text(dir / "p.yaml", cube_pipeline("  - plugin: test_centroid\n  - plugin: test_count\n"));
  CHECK(run_medax("validate '" + file.string() + "'", folder.string(), dir).code == 0);
  const auto ran = run_medax("run '" + file.string() + "' --out '" + (dir / "out").string() + "' --quiet",
                             folder.string(), dir);
  CHECK(ran.code == 0);
  CHECK(check_complete_run(dir / "out")["status"] == "ok");
}

}  // namespace

TEST_CASE("a truncated plugin, cut anywhere, is named as truncated, the others still work", "[faults][plugins]") {
  const auto dir = scratch_dir("faults_plugin_truncated");
  const std::string good = read_text(kGoodSo);
  for (const std::size_t cut : {std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{600}, good.size() / 3,
                                good.size() / 2, good.size() - 4096, good.size() - 1}) {
    INFO("cut at " << cut << " of " << good.size() << " bytes");
    check_isolated(folder_with(dir, "plugins", good.substr(0, cut)), "libbroken.so", "truncated", dir);
  }
}

TEST_CASE("a zero-byte .so, a text file named .so and an executable named .so are named as not plugins",
          "[faults][plugins]") {
  const auto dir = scratch_dir("faults_plugin_foreign");
  check_isolated(folder_with(dir, "zero", ""), "libbroken.so", "not a plugin", dir);
  check_isolated(folder_with(dir, "text", "this is not a shared library\n"), "libbroken.so", "not a plugin", dir);
  check_isolated(folder_with(dir, "exe", read_text("/bin/true")), "libbroken.so", "cannot be loaded", dir);
}

TEST_CASE("a plugin built for another ABI is named with both ABIs, the others still work", "[faults][plugins]") {
  const auto dir = scratch_dir("faults_plugin_abi");
  const fs::path folder = folder_with(dir, "abi", "");
  fs::remove(folder / "libbroken.so");
  fs::copy_file(plugin_dir("bad_abi") / "libmedax_kernel_test_bad_abi.so", folder / "libbroken.so");
  check_isolated(folder, "libbroken.so", "built for medax ABI", dir);
}
