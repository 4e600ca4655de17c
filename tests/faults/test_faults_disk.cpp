// A full disk and a file-size limit hit at every point of a run (issue 13): exit 1 with the
// reason, the previous run untouched, nothing half-written, no debris. Root ignores permission
// bits, so "cannot write" is made by a small tmpfs (this test requires that `mount` works, as it
// does for root in the CI container: it fails rather than skips otherwise) and by RLIMIT_FSIZE.
#include "fault_helpers.hpp"

using namespace medax::test;
namespace fs = std::filesystem;

namespace {

std::string pipeline() {
  return cube_pipeline("  - plugin: test_centroid\n  - plugin: test_count\n") + "outputs:\n  medial: [ma, ply]\n";
}

/// Fills the disk under `dir` but for about `left` bytes.
void fill_leaving(const fs::path& dir, std::size_t left) {
  const fs::space_info space = fs::space(dir);
  const std::size_t fill = space.available > left ? space.available - left : 0;
  write_text(dir / "filler", std::string(fill, 'x'));
}

/// The fault's outcome: success (a complete run), or exit 1 naming the cause with the previous
/// run untouched and no debris left beside it.
void check_write_fault(const Output& r, const fs::path& out, const std::map<std::string, std::string>& before,
                       const std::string& reason) {
  INFO(r.err);
  if (r.code == 0) {
    check_complete_run(out);
    return;
  }
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains(reason));
  CHECK_THAT(r.err, !Catch::Contains("terminate called"));
  if (fs::exists(out / "run.json") && snapshot(out) != before) check_complete_run(out);  // a failed run, published whole
  else CHECK(snapshot(out) == before);
}

}  // namespace

TEST_CASE("a full disk at any point of a run: exit 1 with the reason, previous run intact", "[faults][disk]") {
  ::umount2((binary_dir() / "tests" / "scratch" / "faults_full_disk" / "disk").c_str(), MNT_DETACH);  // a stale one
  const auto dir = scratch_dir("faults_full_disk");
  const fs::path disk = dir / "disk";
  const SmallDisk mounted(disk, 256 * 1024);
  const fs::path out = disk / "out";
  const auto first = write_text(dir / "first.yaml", pipeline());
  REQUIRE(run_medax("run '" + first.string() + "' --out '" + out.string() + "' --quiet", good_plugins(), dir).code == 0);
  const auto file = write_text(dir / "p.yaml", pipeline());
  // Free space from none to more than a run needs, in steps that stop the run at each of its files.
  for (std::size_t left = 0; left <= 48 * 1024; left += 4096) {
    INFO(left << " bytes left");
    const auto before = snapshot(out);
    fill_leaving(disk, left);
    const auto r = run_medax("run '" + file.string() + "' --out '" + out.string() + "' --quiet", good_plugins(), dir);
    check_write_fault(r, out, before, "No space left on device");
    fs::remove(disk / "filler");
    // The next run, with room, cleans up what the failed one left (its staging folder, when even
    // run.json could not be written) and publishes a complete run.
    REQUIRE(run_medax("run '" + file.string() + "' --out '" + out.string() + "' --quiet", good_plugins(), dir).code == 0);
    check_complete_run(out);
    CHECK(debris(disk).empty());
    if (r.code == 0) break;  // enough room: the run went through
  }
}

TEST_CASE("a file-size limit (RLIMIT_FSIZE) at any point of a run: exit 1 with the reason, never SIGXFSZ",
          "[faults][disk]") {
  const auto dir = scratch_dir("faults_fsize");
  const fs::path out = dir / "runs" / "out";
  const auto first = write_text(dir / "first.yaml", pipeline());
  REQUIRE(run_medax("run '" + first.string() + "' --out '" + out.string() + "' --quiet", good_plugins(), dir).code == 0);
  const auto file = write_text(dir / "p.yaml", pipeline());
  for (const rlim_t limit : {0, 1, 100, 300, 400, 550, 1000}) {
    INFO("RLIMIT_FSIZE " << limit);
    const auto before = snapshot(out);
    const Output r = run_medax_capped("run '" + file.string() + "' --out '" + out.string() + "' --quiet",
                                      good_plugins(), limit);
    check_write_fault(r, out, before, "File too large");
  }
  REQUIRE(run_medax("run '" + file.string() + "' --out '" + out.string() + "' --quiet", good_plugins(), dir).code == 0);
  check_complete_run(out);
  CHECK(debris(dir / "runs").empty());
}
