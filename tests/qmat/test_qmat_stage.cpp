// The `qmat` stage as shipped: loaded from the built plugin, its declared parameters, its
// refusals, the saved-vertex contract (`selected` column) and the target rule.
#include "loaded_stage.hpp"
#include "qmat_test_inputs.hpp"

#include <medax/stage.hpp>

#include <catch2/catch.hpp>

using namespace medax;

namespace {

const Property<int> kSelected{Element::Vertex, "selected"};

struct Loaded : test::LoadedStage<SimplificationStage> {
  Loaded() : LoadedStage(MEDAX_QMAT_PLUGIN, "qmat") {}
};

}  // namespace

TEST_CASE("qmat stage: declared parameters, package and docs", "[qmat][stage]") {
  const Loaded loaded;
  const StageInfo& info = loaded.stage->info();
  CHECK(info.role == Role::Simplification);
  CHECK(info.doc == "docs/plugins/qmat.md");
  CHECK(loaded.stage->package->name == "qmat");
  std::map<std::string, const ParamSpec*> params;
  for (const ParamSpec& p : info.params) {
    params[p.name] = &p;
    CHECK(!p.doc.empty());
  }
  CHECK(params.at("stability_weight")->default_text() == "1e-05");
  CHECK(params.at("cone_terms")->choices == std::vector<std::string>{"qmat_code", "clean"});
  CHECK(params.at("keep")->default_text() == "auto");
  CHECK(params.at("correct_spheres")->default_text() == "false");
  CHECK(std::filesystem::exists(test::source_dir() / info.doc));
}

TEST_CASE("qmat stage: simplifies to the target, keeps the selected column, refuses what it cannot use",
          "[qmat][stage]") {
  const Loaded loaded;
  Shape shape;
  shape.mesh = read_mesh(test::data_dir() / "joint.off");
  const MedialComplex axis = test::voronoi_axis(shape.mesh);
  BasicContext ctx;

  MedialComplex medial = axis;
  loaded.create({{"target_vertices", 120LL}})->simplify(shape, medial, ctx);
  CHECK(medial.num_vertices() == 120);

  // Saved spheres: target 0 means "only the saved ones (plus one per component without one)".
  MedialComplex selected = axis;
  std::vector<int>& flags = selected.add(kSelected, 0);
  for (std::size_t v = 0; v < flags.size(); v += flags.size() / 20) flags[v] = 1;
  const long long n_saved = std::count(flags.begin(), flags.end(), 1);
  loaded.create()->simplify(shape, selected, ctx);
  REQUIRE(selected.has(kSelected));
  const std::vector<int>& out_flags = selected.get(kSelected);
  CHECK(std::count(out_flags.begin(), out_flags.end(), 1) == n_saved);
  CHECK(selected.num_vertices() >= static_cast<std::size_t>(n_saved));

  Scene scene;
  scene.shape = shape;
  scene.medial = axis;
  CHECK_THROWS_WITH(loaded.create({{"keep", std::string("selected")}})->prepare(scene),
                    Catch::Contains("no int vertex column `selected`"));
  MedialComplex plain = axis;
  CHECK_THROWS_WITH(loaded.create()->simplify(shape, plain, ctx), Catch::Contains("set target_vertices"));
  Scene no_mesh;
  no_mesh.medial = axis;
  CHECK_THROWS_WITH(loaded.create({{"correct_spheres", true}})->prepare(no_mesh),
                    Catch::Contains("needs the surface mesh"));
}
