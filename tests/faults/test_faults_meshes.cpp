// Every bad mesh of tests/data/bad through every shipped pipeline (issue 13): validation passes
// (the pipeline is fine), the run exits 1 naming the file and the reason, never a crash and never
// exit 0. Every shipped pipeline starts with `repair` or fails in the reader, so the full run is cheap.
// A point-cloud pipeline given a mesh that reads but is broken as a mesh refuses it for having no
// points: the mesh's defect does not concern it.
#include "fault_helpers.hpp"

using namespace medax::test;
namespace fs = std::filesystem;

namespace {

/// Each bad mesh and a word of the reason it must be refused with.
const std::vector<std::pair<std::string, std::string>> kBadMeshes{
    {"bad_index.obj", "refers to vertex 9"},
    {"bad_index.off", "refers to vertex 7"},
    {"empty.off", "empty file"},
    {"huge_face.off", "announces 999999999 corners"},
    {"huge_header.off", "truncated or its header is wrong"},
    {"huge_header.ply", "truncated or its header is wrong"},
    {"huge_header.stl", "truncated or its header is wrong"},
    {"inf.obj", "non-finite coordinate"},
    {"nan.off", "non-finite coordinate"},
    {"nan.stl", "non-finite coordinate"},
    {"negative_index.ply", "-1"},
    {"points_only.obj", "no faces"},
    {"points_only.ply", "no faces"},
    {"truncated.off", "truncated"},
    {"truncated.ply", "truncated"},
    {"cow.off", "self-intersecting"},
    {"thingi10k-68251.stl", "non-manifold edges"},
};

std::vector<fs::path> shipped_pipelines() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(fs::path(MEDAX_SOURCE_DIR) / "pipelines"))
    if (entry.path().extension() == ".yaml") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

bool is_point_cloud_pipeline(const fs::path& pipeline) {
  return pipeline.filename().string().rfind("pointcloud_", 0) == 0;
}

/// The shipped plugins of this build (MEDAX_PLUGIN_PATH empty: the built-in folder).
const std::string kShipped;

}  // namespace

TEST_CASE("every mesh of tests/data/bad is listed here", "[faults][meshes]") {
  for (const auto& entry : fs::directory_iterator(fs::path(MEDAX_TEST_DATA_DIR) / "bad")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".md" || entry.path().extension() == ".ma") continue;  // docs; medial files
    INFO(name);
    CHECK(std::any_of(kBadMeshes.begin(), kBadMeshes.end(), [&](const auto& m) { return m.first == name; }));
  }
}

TEST_CASE("bad meshes through every shipped pipeline exit 1 naming the file and the reason", "[faults][meshes]") {
  ::umount2((binary_dir() / "tests" / "scratch" / "faults_bad_meshes" / "disk").c_str(), MNT_DETACH);  // a stale one
  const auto dir = scratch_dir("faults_bad_meshes");
  // The ~150 run folders go to a tmpfs: their fsyncs would cost more than the runs themselves.
  const SmallDisk outputs(dir / "disk", 64 << 20);
  const auto pipelines = shipped_pipelines();
  REQUIRE(pipelines.size() >= 8);
  for (const fs::path& pipeline : pipelines) {
    INFO(pipeline.filename().string());
    const auto valid = run_medax("validate '" + pipeline.string() + "' --input '" + data_file("cube.off") + "'", kShipped, dir);
    INFO(valid.err);
    CHECK(valid.code == 0);  // the pipeline is fine: what fails below is the mesh
    if (valid.code != 0) continue;
    for (const auto& [mesh, reason] : kBadMeshes) {
      const std::string input = data_file("bad/" + mesh);
      INFO("on " << mesh);
      const std::string args = "'" + pipeline.string() + "' --input '" + input + "'";
      const fs::path out = dir / "disk" / "out";
      fs::remove_all(out);
      const auto r = run_medax("run " + args + " --out '" + out.string() + "' --quiet", kShipped, dir);
      INFO(r.err);
      CHECK(r.code == 1);
      CHECK_THAT(r.err, !Catch::Contains("terminate called"));
      if (fs::exists(out / "results.csv")) {
        // A sweep: each job failed; results.csv holds the reason per row.
        const std::string results = read_text(out / "results.csv");
        CHECK_THAT(results, Catch::Contains(fs::path(mesh).stem().string()));
        CHECK_THAT(results, Catch::Contains(reason));
        CHECK_THAT(results, !Catch::Contains(",ok,"));
      } else if (is_point_cloud_pipeline(pipeline) && r.err.find("the shape has no points") != std::string::npos) {
        CHECK(check_complete_run(out)["status"] == "failed");
      } else {
        CHECK_THAT(r.err, Catch::Contains(mesh));
        CHECK_THAT(r.err, Catch::Contains(reason));
        CHECK(check_complete_run(out)["status"] == "failed");
      }
    }
  }
}
