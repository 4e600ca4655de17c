// The sheet graph (connectivity output): sheets and curves, adjacent through singular paths.
#include "fixtures.hpp"
#include "sheet_graph.hpp"

#include <medax/services/topology.hpp>
#include <medax/union_find.hpp>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <sstream>

using namespace medax;
using namespace medax::durix;

namespace {

DurixResult run(const SurfaceMesh& mesh) {
  const EpsilonOracle oracle(0.01 * bbox_diagonal(mesh.vertices));
  return durix_medial_axis(mesh, oracle);
}

/// Components of the graph over sheets, both kinds of adjacency.
std::size_t graph_components(const SheetGraph& g) {
  UnionFind components(g.sheets.size());
  for (const SheetAdjacency& a : g.adjacency) components.unite(a.a, a.b);
  return components.count();
}

}  // namespace

TEST_CASE("durix: the sheet graph has every sheet and is connected like the complex", "[durix][sheet_graph]") {
  for (const char* name : {"box", "torus", "ellipsoid"}) {
    INFO(name);
    const DurixResult r = run(durix::test::fixture(name));
    const SheetGraph g = sheet_graph(r.medial);
    REQUIRE(g.sheets.size() == r.report.sheets + r.report.curve_sheets);
    // A connected complex has a connected sheet graph.
    CHECK(services::complex_topology(r.medial).b0 == 1);
    CHECK(graph_components(g) == 1);
    // Areas add up to the complex's; every face sheet has faces, every curve has length.
    double area = 0;
    for (const auto& t : r.medial.faces)
      area += 0.5 * (r.medial.centres[t[1]] - r.medial.centres[t[0]])
                        .cross(r.medial.centres[t[2]] - r.medial.centres[t[0]])
                        .norm();
    double graph_area = 0;
    for (const SheetNode& s : g.sheets) {
      graph_area += s.area;
      CHECK((s.curve ? s.length > 0 : s.polygons > 0));
    }
    CHECK(graph_area == Approx(area).epsilon(1e-9));
    // Every singular edge separates at least two sheets, so the singular adjacencies count at
    // least as many edge-sheet-pairs as there are singular edges (a forced edge may have one
    // sheet on both sides, when the cut it belongs to did not separate).
    const auto& type = r.medial.get(kPathType);
    const auto singular = static_cast<std::size_t>(std::count(type.begin(), type.end(), int(kSingular)));
    std::size_t pairs = 0;
    for (const SheetAdjacency& a : g.adjacency) {
      CHECK(a.a < a.b);
      pairs += a.singular_edges;
    }
    CHECK(pairs >= singular);
    if (std::string(name) == "box") CHECK(singular > 0);
  }
}

TEST_CASE("durix: the sheet graph JSON scales to the input frame", "[durix][sheet_graph]") {
  const DurixResult r = run(durix::test::fixture("box"));
  const SheetGraph g = sheet_graph(r.medial);
  SheetGraph twice = g;
  twice.input_scale = 2.0;
  std::ostringstream one, two, written;
  write_sheet_graph_json(one, g);
  write_sheet_graph_json(two, twice);
  kSheetGraph.write(twice, written);
  CHECK(written.str() == two.str());
  const auto a = nlohmann::json::parse(one.str()), b = nlohmann::json::parse(two.str());
  REQUIRE(a["sheets"].size() == g.sheets.size());
  REQUIRE(a["adjacency"].size() == g.adjacency.size());
  for (std::size_t i = 0; i < g.sheets.size(); ++i) {
    CHECK(a["sheets"][i]["area"].get<double>() == Approx(g.sheets[i].area));
    CHECK(b["sheets"][i]["area"].get<double>() == Approx(4 * g.sheets[i].area));
  }
  CHECK_THROWS_WITH(sheet_graph(MedialComplex{}), Catch::Contains("not a durix output"));
}
