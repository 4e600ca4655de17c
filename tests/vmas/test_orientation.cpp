// vmas on an inward-facing mesh (issue 13): the failure names the orientation and the fix, and
// the mesh the repair service flips outward runs.
#include "stages.hpp"

#include <medax/io.hpp>
#include <medax/services/mesh_check.hpp>
#include <test_paths.hpp>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace medax;

namespace {

/// tests/data/ellipsoid.off with every face reversed: closed, consistent, facing inward.
SurfaceMesh inward_ellipsoid() {
  SurfaceMesh mesh = read_mesh(std::filesystem::path(MEDAX_TEST_DATA_DIR) / "ellipsoid.off");
  for (Tri& f : mesh.faces) std::swap(f[1], f[2]);
  return mesh;
}

MedialComplex run_vmas(const SurfaceMesh& mesh) {
  vmas::VmasStage stage;
  ParamSet params;
  params.set("target_spheres", ParamValue(8LL));
  stage.configure(params);
  Scene scene;
  scene.shape.mesh = mesh;
  stage.prepare(scene);
  BasicContext ctx(1);
  return stage.extract(scene.shape, ctx);
}

}  // namespace

TEST_CASE("vmas on an inward-facing mesh names the orientation and the repair stage", "[vmas][orientation]") {
  const SurfaceMesh mesh = inward_ellipsoid();
  const services::MeshReport report = services::check_mesh(mesh, {false});
  REQUIRE(report.closed);
  REQUIRE(report.relative_volume < 0);
  CHECK_THROWS_WITH(run_vmas(mesh), Catch::Contains("no shrinking ball could be computed") &&
                                        Catch::Contains("faces point inward") &&
                                        Catch::Contains("plugin: repair") && Catch::Contains("reorient"));
}

TEST_CASE("vmas runs on the inward-facing mesh once repair has flipped it", "[vmas][orientation]") {
  const services::RepairResult repaired = services::repair_mesh(inward_ellipsoid());
  REQUIRE(repaired.ok());
  CHECK(repaired.after.signed_volume > 0);
  const MedialComplex mc = run_vmas(repaired.mesh);
  CHECK(mc.num_vertices() == 8);
}
