// The duality structure and half-edge navigation (notes §2.3), checked numerically, and the
// oriented sheets of a finished run (notes §5.4).
#include "dual.hpp"
#include "engine.hpp"
#include "fixtures.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <numeric>
#include <set>

using namespace medax;
using namespace medax::durix;

namespace {

/// Every medial half-edge of the current solid (both corners of every volumetric face of every
/// medial edge).
std::vector<HalfEdge> half_edges(const Dual& d) {
  std::vector<HalfEdge> out;
  d.for_each_solid_facet([&](const Facet& t) { d.for_each_half_edge(t, [&](const HalfEdge& h) { out.push_back(h); }); });
  return out;
}

}  // namespace

TEST_CASE("durix: half-edge navigation is consistent and oriented as the notes say", "[durix][dual]") {
  for (const std::string name : {"sphere", "ellipsoid", "box", "torus"}) {
    INFO(name);
    const SurfaceMesh m = durix::test::fixture(name);
    const Dual d(m.vertices, m.faces);
    const std::vector<HalfEdge> all = half_edges(d);
    REQUIRE(!all.empty());
    std::size_t oriented = 0, measured = 0;
    for (const HalfEdge& h : all) {
      // next/prev walk the same half-face; flip and side_nbr are involutions.
      CHECK(d.start(d.next(h)) == d.end(h));
      CHECK(d.prev(d.next(h)) == h);
      CHECK(d.flip(d.flip(h)) == h);
      CHECK(d.start(d.flip(h)) == d.end(h));
      CHECK(d.side_nbr(d.side_nbr(h)) == h);
      CHECK(d.end(d.side_nbr(h)) == d.start(h));
      CHECK(d.face(d.side_nbr(h)) != kNoId);
      // c(N-) -> c(N+) points along +n_t for t = (u, v, w): the half-edge runs N+ -> N-.
      const Index w = d.third(h);
      const Vec3 n = (d.point(h.v) - d.point(h.u)).cross(d.point(w) - d.point(h.u));
      const Vec3 step = d.centre(d.end(h)) - d.centre(d.start(h));
      if (d.flat(d.start(h)) || d.flat(d.end(h)) || step.norm() < 1e-9 * n.norm()) continue;
      ++measured;
      oriented += step.dot(n) < 0;
    }
    CHECK(oriented == measured);
    // Each half-face polygon turns counter-clockwise seen from its corner (normal u - v).
    std::size_t ccw = 0, polygons = 0;
    std::map<std::pair<EdgeId, Index>, bool> done;
    for (const HalfEdge& h0 : all) {
      const EdgeId e = d.face(h0);
      if (done[{e, h0.u}]) continue;
      done[{e, h0.u}] = true;
      Vec3 area = Vec3::Zero();
      HalfEdge h = h0;
      bool degenerate = false;
      for (int i = 0; i < 10000; ++i) {
        degenerate |= d.flat(d.start(h));
        area += d.centre(d.start(h)).cross(d.centre(d.end(h)));
        h = d.next(h);
        if (h == h0) break;
      }
      REQUIRE(h == h0);
      const Vec3 axis = d.point(h0.u) - d.point(h0.v);
      if (degenerate || area.norm() < 1e-12 * axis.squaredNorm()) continue;
      ++polygons;
      ccw += area.dot(axis) > 0;
    }
    if (name != "torus") CHECK(polygons > 0);  // the grid torus: every polygon has a flat cell
    CHECK(ccw == polygons);
  }
}

TEST_CASE("durix: every sheet has one or two oriented sides", "[durix][dual]") {
  for (const char* name : {"ellipsoid", "box", "torus", "capsule"}) {
    INFO(name);
    const SurfaceMesh m = durix::test::fixture(name);
    Dual d(m.vertices, m.faces);
    DurixReport report;
    const DurixOptions options;
    const EpsilonOracle oracle(0.01 * bbox_diagonal(m.vertices));
    Engine engine(d, oracle, options, report, {});
    engine.run({});
    // Half-faces (face, corner), joined across regular edges by side_nbr: the oriented sheets.
    std::map<std::pair<EdgeId, Index>, std::size_t> id;
    std::vector<std::size_t> parent;
    const auto node = [&](const HalfEdge& h) {
      const auto key = std::make_pair(d.face(h), h.u);
      const auto it = id.find(key);
      if (it != id.end()) return it->second;
      id.emplace(key, parent.size());
      parent.push_back(parent.size());
      return parent.size() - 1;
    };
    const auto find = [&](std::size_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const HalfEdge& h : half_edges(d)) {
      const std::size_t a = node(h);
      if (d.degree(h.t) != 2 || d.forced(h.t)) continue;
      const HalfEdge g = d.side_nbr(h);
      if (d.label(d.face(g)) != d.label(d.face(h))) continue;
      parent[find(a)] = find(node(g));
    }
    std::map<int, std::set<std::size_t>> sides;
    for (const auto& [key, index] : id) sides[d.label(key.first)].insert(find(index));
    REQUIRE(!sides.empty());
    for (const auto& [label, roots] : sides) {
      INFO("sheet " << label);
      CHECK(label >= 0);
      CHECK((roots.size() == 1 || roots.size() == 2));
    }
  }
}
