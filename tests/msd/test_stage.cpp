// The msd stage end to end on tests/data/ellipsoid.off with its VMAS medial mesh
// (tests/data/msd_ellipsoid_vmas.ma), and the msd_medial stage on a file in the authors' format.
#include "mesh_checks.hpp"
#include "output.hpp"
#include "stages.hpp"

#include <medax/io.hpp>
#include <medax/representation_size.hpp>

#include "../support/capturing_context.hpp"
#include "../support/test_paths.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <sstream>

using namespace medax;
using namespace medax::msd;
using medax::msd::checks::check_closed_manifold;

TEST_CASE("msd stage on the ellipsoid: the skeleton replaces M, outputs are written, Ŝ is published") {
  Scene scene;
  scene.shape.mesh = read_mesh(medax::test::data_dir() / "ellipsoid.off");
  scene.medial = read_ma(medax::test::data_dir() / "msd_ellipsoid_vmas.ma");
  const MedialMesh m = MedialMesh::from_complex(*scene.medial);
  MsdStage stage;
  ParamSet params;
  params.set("n_init", 3LL);
  params.set("first_iterations", 6LL);
  params.set("add_every", 4LL);
  params.set("max_iterations", 10LL);
  params.set("search_sphere_vertices", 100LL);
  params.set("sphere_vertices", 200LL);
  params.set("reconstruction", std::string("sdf"));
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
