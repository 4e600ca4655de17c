// The msd stage end to end on tests/data/ellipsoid.off with its VMAS medial mesh
// (tests/data/msd_ellipsoid_vmas.ma): Ŝ by the grid, refinement on and off with the grid-free Ŝ;
// and the msd_medial stage on a file in the authors' format.
#include "mesh_checks.hpp"
#include "output.hpp"
#include "stages.hpp"

#include <medax/io.hpp>
#include <medax/representation_size.hpp>
#include <medax/services/closest_point.hpp>

#include <nlohmann/json.hpp>

#include "../support/capturing_context.hpp"
#include "../support/test_paths.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <memory>
#include <sstream>

using namespace medax;
using namespace medax::msd;
using medax::msd::checks::check_closed_manifold;
using medax::msd::checks::two_sided_error;

namespace {

/// A short optimisation on the ellipsoid (3 sites, 10 evaluations, small templates).
ParamSet short_run(bool refine, const std::string& reconstruction) {
  ParamSet params;
  params.set("n_init", 3LL);
  params.set("first_iterations", 6LL);
  params.set("add_every", 4LL);
  params.set("max_iterations", 10LL);
  params.set("search_sphere_vertices", 100LL);
  params.set("sphere_vertices", 200LL);
  params.set("refine", refine);
  params.set("reconstruction", reconstruction);
  return params;
}

struct MsdRun {
  Scene scene;
  std::unique_ptr<test::CapturingContext> ctx = std::make_unique<test::CapturingContext>(0, false, "msd");
  nlohmann::json summary() const { return nlohmann::json::parse(ctx->files.at("msd_msd.json")); }
  /// Vertices of <id>_primitives.ply, from its header.
  std::size_t ply_vertices() const {
    std::istringstream in(ctx->files.at("msd_primitives.ply"));
    for (std::string line; std::getline(in, line);)
      if (line.rfind("element vertex ", 0) == 0) return std::stoul(line.substr(15));
    return 0;
  }
};

MsdRun run_msd(const ParamSet& params) {
  MsdRun run;
  run.scene.shape.mesh = read_mesh(medax::test::data_dir() / "ellipsoid.off");
  run.scene.medial = read_ma(medax::test::data_dir() / "msd_ellipsoid_vmas.ma");
  MsdStage stage;
  stage.configure(params);
  stage.set_id("msd");
  stage.prepare(run.scene);
  stage.run(run.scene, *run.ctx);
  return run;
}

}  // namespace

TEST_CASE("msd stage on the ellipsoid: the skeleton replaces M, outputs are written, Ŝ is published") {
  Scene scene;
  scene.shape.mesh = read_mesh(medax::test::data_dir() / "ellipsoid.off");
  scene.medial = read_ma(medax::test::data_dir() / "msd_ellipsoid_vmas.ma");
  const MedialMesh m = MedialMesh::from_complex(*scene.medial);
  MsdStage stage;
  ParamSet params = short_run(false, "sdf");
  params.set("reconstruction_resolution", 64LL);
  stage.configure(params);
  stage.set_id("msd");
  test::CapturingContext ctx(0, false, "msd");
  stage.prepare(scene);
  stage.run(scene, ctx);

  REQUIRE(scene.medial);
  const MedialComplex& skeleton = *scene.medial;
  REQUIRE(skeleton.num_vertices() >= 3);
  CHECK_NOTHROW(skeleton.validate());
  for (std::size_t v = 0; v < skeleton.num_vertices(); ++v) {
    CHECK(m.closest_point(skeleton.centres[v]).distance < 1e-9);
    CHECK(skeleton.radii[v] > 0);
  }
  CHECK(skeleton.get(kIsSite)[0] == 1);
  REQUIRE(ctx.files.count("msd_msd.json"));
  CHECK_THAT(ctx.files["msd_msd.json"], Catch::Contains("\"N_d\""));
  REQUIRE(ctx.files.count("msd_primitives.ply"));
  CHECK_THAT(ctx.files["msd_primitives.ply"], Catch::Contains("property int primitive"));
  // Ŝ and the MSD counts for the evaluation stages.
  const ReconstructedSurface* rebuilt = ctx.data().find(kReconstructedSurface);
  REQUIRE(rebuilt);
  CHECK(rebuilt->surface.faces.size() > 100);
  CHECK_THAT(rebuilt->method, Catch::Contains("64 voxels"));
  check_closed_manifold(rebuilt->surface.faces, rebuilt->surface.vertices.size());
  const RepresentationSize* size = ctx.data().find(kRepresentationSize);
  REQUIRE(size);
  CHECK(size->discrete == skeleton.num_vertices() + skeleton.edges.size() + skeleton.faces.size());
  CHECK(size->continuous > 3 * skeleton.num_vertices());
}

TEST_CASE("msd stage with and without refinement: the same skeleton, N_c of the final primitives, ε̄ not raised") {
  const MsdRun fitted = run_msd(short_run(false, "union"));
  const MsdRun refined = run_msd(short_run(true, "union"));
  REQUIRE(fitted.scene.medial);
  REQUIRE(refined.scene.medial);
  CHECK(fitted.scene.medial->centres == refined.scene.medial->centres);  // refinement leaves the skeleton
  const nlohmann::json off = fitted.summary(), on = refined.summary();
  CHECK(off["refinement"]["enabled"] == false);
  CHECK(on["refinement"]["enabled"] == true);
  const std::size_t skeleton_vertices = refined.scene.medial->num_vertices();
  const std::size_t primitives = skeleton_vertices + refined.scene.medial->edges.size() +
                                 refined.scene.medial->faces.size();
  const std::size_t refined_count = on["refinement"]["refined"], unrefined_count = on["refinement"]["unrefined"];
  CHECK(refined_count + unrefined_count + on["failed_primitives"].get<std::size_t>() == primitives);
  CHECK(refined_count > 0);
  CHECK(on["refinement"]["unrefined_notes"].size() == unrefined_count);
  CHECK(on["seconds"]["refinement"].get<double>() > 0);
  // N_c = Σ|V(T_P)| + 3·#v over the primitives written, fitted or refined.
  for (const MsdRun* run : {&fitted, &refined})
    CHECK(run->summary()["N_c"].get<std::size_t>() == run->ply_vertices() + 3 * skeleton_vertices);
  CHECK(off["N_d"] == on["N_d"]);
  // Ŝ without a grid from each; the refined one is no farther from S.
  const SurfaceMesh& surface = refined.scene.shape.mesh;
  const ReconstructedSurface* before = fitted.ctx->data().find(kReconstructedSurface);
  const ReconstructedSurface* after = refined.ctx->data().find(kReconstructedSurface);
  REQUIRE(before);
  REQUIRE(after);
  CHECK_THAT(after->method, Catch::Contains("without a grid"));
  const double error_before = two_sided_error(surface, before->surface);
  const double error_after = two_sided_error(surface, after->surface);
  CHECK(error_after <= error_before);
  CHECK(error_after < 0.5 * error_before);  // refinement puts S's own triangles into Ŝ
}

TEST_CASE("msd_medial reads the authors' JSON into the scene in the working frame") {
  const auto path = medax::test::scratch_dir("msd_medial") / "input-ma.json";
  std::ofstream(path) << R"({"vertices": [[0, {"pos": ["0", "0", "0"]}], [1, {"pos": ["1/10", "0", "0"]}]],
                            "edges": [[0, {"vidx": [0, 1]}]], "triangles": []})";
  Scene scene;
  scene.shape.mesh = read_mesh(medax::test::data_dir() / "ellipsoid.off");
  MsdMedialStage stage;
  ParamSet params;
  params.set("medial_file", path.string());
  stage.configure(params);
  BasicContext ctx;
  stage.run(scene, ctx);
  REQUIRE(scene.medial);
  CHECK(scene.medial->num_vertices() == 2);
  CHECK(scene.medial->centres[1].x() == Approx(0.1));
  CHECK(scene.medial->radii[0] > 0);  // the distance to S
  MsdMedialStage empty;
  CHECK_THROWS_WITH(empty.check_params(), Catch::Contains("medial_file"));
}
