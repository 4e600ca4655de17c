#include "fixtures.hpp"

#include "dual.hpp"

#include <medax/services/delaunay.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

namespace medax::durix::test {

SurfaceMesh to_delaunay(const SurfaceMesh& mesh) {
  DelaunayMeshReport report;
  SurfaceMesh out = make_delaunay_mesh(mesh, {}, &report);
  REQUIRE(check_delaunay_mesh(out).ok());
  return out;
}

SurfaceMesh fixture(const std::string& name) {
  SurfaceMesh m;
  if (name == "sphere") {
    m = testing::make_sphere(1.0, 3);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    for (Vec3& p : m.vertices) p *= 1.0 + jitter(rng);
  } else if (name == "ellipsoid") {
    m = testing::make_ellipsoid(1.5, 1.0, 0.6, 3);
  } else if (name == "box") {
    m = testing::make_box(1.0, 0.7, 0.4, 6);
  } else if (name == "torus") {
    m = testing::make_torus(1.0, 0.35, 48, 16);
  } else if (name == "capsule") {
    m = testing::make_capsule(0.3, 0.8, 24);
  } else {
    FAIL("unknown fixture " << name);
  }
  return to_delaunay(m);
}

SurfaceMesh cube_union(const std::vector<std::array<int, 3>>& cells, int n) {
  const std::set<std::array<int, 3>> filled(cells.begin(), cells.end());
  SurfaceMesh m;
  std::map<std::array<int, 3>, Index> vertex;  // grid point (in 1/n units) -> index
  const auto at = [&](std::array<int, 3> g) {
    const auto [it, inserted] = vertex.emplace(g, static_cast<Index>(m.vertices.size()));
    if (inserted) m.vertices.emplace_back(double(g[0]) / n, double(g[1]) / n, double(g[2]) / n);
    return it->second;
  };
  for (const auto& c : cells)
    for (int axis = 0; axis < 3; ++axis)
      for (int side : {-1, 1}) {
        std::array<int, 3> neighbour = c;
        neighbour[axis] += side;
        if (filled.count(neighbour)) continue;
        // Tangent axes u, v with u × v = the outward normal.
        int u = (axis + 1) % 3, v = (axis + 2) % 3;
        if (side < 0) std::swap(u, v);
        std::array<int, 3> origin = {c[0] * n, c[1] * n, c[2] * n};
        if (side > 0) origin[axis] += n;
        const auto grid = [&](int i, int j) {
          std::array<int, 3> g = origin;
          g[u] += i;
          g[v] += j;
          return at(g);
        };
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            const Index a = grid(i, j), b = grid(i + 1, j), d = grid(i + 1, j + 1), e = grid(i, j + 1);
            m.faces.push_back({a, b, d});
            m.faces.push_back({a, d, e});
          }
      }
  return m;
}

SurfaceMesh bumped_ellipsoid(double height) {
  SurfaceMesh m = testing::make_ellipsoid(1.2, 1.0, 0.8, 4);
  const double width = 0.15;
  for (Vec3& p : m.vertices) {
    if (p.z() <= 0) continue;
    const double r2 = p.x() * p.x() + p.y() * p.y();
    p.z() += height * std::exp(-r2 / (width * width));
  }
  return to_delaunay(m);
}

namespace {

using Quad = std::array<Index, 4>;

Quad sorted(std::array<Index, 4> q) {
  std::sort(q.begin(), q.end());
  return q;
}

}  // namespace

void check_invariants(const SurfaceMesh& input, const DurixResult& r, double epsilon) {
  const MedialComplex& mc = r.medial;
  const DurixReport& rep = r.report;
  REQUIRE_NOTHROW(mc.validate());
  REQUIRE(mc.generators.size() == mc.num_vertices());

  // V(M_w) ⊆ V(input), positions unchanged.
  REQUIRE(r.surface_vertex.size() == r.surface.vertices.size());
  for (std::size_t i = 0; i < r.surface_vertex.size(); ++i) {
    REQUIRE(r.surface_vertex[i] < input.vertices.size());
    CHECK(r.surface.vertices[i] == input.vertices[r.surface_vertex[i]]);
  }

  // Duality (§5.1): the interior dual of M_w recomputed from scratch (a fresh tetrahedralization
  // of V(M_w) and its interior) has exactly the output's nodes, Voronoi edges and faces. The
  // non-flat interior cells are also confirmed by an independent inside test of their centroid.
  Dual fresh(r.surface.vertices, r.surface.faces);
  std::set<Quad> expected_nodes;
  std::size_t fresh_facets = 0, fresh_faces = 0;
  services::InsideTest inside(r.surface);
  for (CellId c = 0; c < fresh.num_cells(); ++c) {
    const auto& q = fresh.cell(c);
    Vec3 centroid = Vec3::Zero();
    for (Index v : q) centroid += r.surface.vertices[v];
    const Vec3 &p0 = r.surface.vertices[q[0]], &p1 = r.surface.vertices[q[1]], &p2 = r.surface.vertices[q[2]],
               &p3 = r.surface.vertices[q[3]];
    const double volume = (p1 - p0).dot((p2 - p0).cross(p3 - p0));
    const double scale = (p1 - p0).norm() * (p2 - p0).norm() * (p3 - p0).norm();
    if (volume > 1e-6 * scale) CHECK(fresh.solid(c) == inside.inside(centroid / 4.0));
    if (!fresh.solid(c)) continue;
    expected_nodes.insert(sorted({r.surface_vertex[q[0]], r.surface_vertex[q[1]], r.surface_vertex[q[2]],
                                  r.surface_vertex[q[3]]}));
    for (int k = 0; k < 4; ++k)
      if (fresh.solid(fresh.neighbour(c, k)) && fresh.neighbour(c, k) > c) ++fresh_facets;
  }
  for (EdgeId e = 0; e < fresh.num_edges(); ++e) fresh_faces += fresh.volumetric(e);
  std::set<Quad> nodes;
  const auto& flat = mc.get(kNodeFlat);
  for (std::size_t i = 0; i < mc.num_vertices(); ++i) {
    const auto& g = mc.generators[i];
    REQUIRE(g.size() == 4);
    nodes.insert(sorted({g[0], g[1], g[2], g[3]}));
    if (flat[i]) continue;  // four cocircular corners: no well-defined sphere (Appendix A)
    for (Index v : g) {
      const double dist = (input.vertices[v] - mc.centres[i]).norm();
      CHECK(std::abs(dist - mc.radii[i]) <= 1e-6 * std::max(1.0, mc.radii[i]));
    }
  }
  CHECK(nodes.size() == mc.num_vertices());
  CHECK(nodes == expected_nodes);
  const auto& path_type = mc.get(kPathType);
  const std::size_t voronoi_edges =
      static_cast<std::size_t>(std::count_if(path_type.begin(), path_type.end(), [](int t) { return t >= 0; }));
  CHECK(voronoi_edges == fresh_facets);
  CHECK(rep.medial_edges == fresh_facets);
  CHECK(rep.medial_faces == fresh_faces);

  // Homotopy (§5.2): χ(M) = χ(M_w) / 2.
  const auto mt = services::complex_topology(mc);
  const auto st = services::surface_topology(r.surface);
  CHECK(st.closed());
  CHECK(2 * mt.euler == st.complex.euler);
  CHECK(mt.b0 == st.complex.b0);

  // Manifold sheets (§5.4): per Voronoi edge, the sheets of the polygons around it.
  std::map<std::pair<Index, Index>, std::vector<int>> around;
  const auto& face_sheet = mc.get(kFaceSheet);
  for (std::size_t f = 0; f < mc.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      Index a = mc.faces[f][i], b = mc.faces[f][(i + 1) % 3];
      if (a > b) std::swap(a, b);
      around[{a, b}].push_back(face_sheet[f]);
    }
  const auto& degree = mc.get(kEdgeDegree);
  for (std::size_t e = 0; e < mc.edges.size(); ++e) {
    if (path_type[e] < 0) continue;
    Index a = mc.edges[e][0], b = mc.edges[e][1];
    if (a > b) std::swap(a, b);
    const auto it = around.find({a, b});
    const std::vector<int> sheets = it == around.end() ? std::vector<int>{} : it->second;
    CHECK(static_cast<int>(sheets.size()) == degree[e]);
    CHECK(path_type[e] != kProblematic);
    for (int s : sheets) CHECK(s >= 0);
    if (path_type[e] == kRegular) CHECK((sheets.size() == 2 && sheets[0] == sheets[1]));
    if (degree[e] == 3) CHECK(!(sheets[0] == sheets[1] && sheets[1] == sheets[2]));
  }
  CHECK(rep.problematic_left == 0);

  // Paths (§5.5): closed, induced loops along M_w edges, boundary edges traced twice.
  CHECK(rep.unclosed_paths == 0);
  CHECK(rep.loop_corner_errors == 0);
  CHECK(rep.boundary_multiplicity_errors == 0);

  // ε (§5.6): removed input vertices stay within ε of the output balls (upper bound).
  CHECK(rep.max_removed_excess <= epsilon * (1 + 1e-9));

  // Segmentation and correspondence sizes.
  CHECK(r.vertex_sheet.size() == input.vertices.size());
  CHECK(r.face_sheet.size() == input.faces.size());
  CHECK(r.surface_face_node.size() == r.surface.faces.size());
  for (Index n : r.surface_face_node) CHECK(n < mc.num_vertices());
}

}  // namespace medax::durix::test
