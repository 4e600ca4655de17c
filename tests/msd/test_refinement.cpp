// MSD feature-preserving refinement (paper §5.4; notes §2.8, §7 item 9) on analytic shapes: the
// refined primitive contains S's vertices and triangles exactly where it covers S, and stays
// closed, 2-manifold, outward and consistent along its direction field.
#include "fitting.hpp"
#include "mesh_checks.hpp"
#include "refinement.hpp"

#include <medax/testing/shapes.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <set>

using namespace medax;
using namespace medax::msd;
using medax::msd::checks::check_closed_manifold;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

SkeletonElement vertex_at(const Vec3& p) { return {ElementKind::Vertex, {0, 0, 0}, {p, p, p}}; }
SkeletonElement edge_between(const Vec3& a, const Vec3& b) { return {ElementKind::Edge, {0, 1, 0}, {a, b, b}}; }

/// Prism over the triangle (c0, c1, c2) for z ∈ [−h, h]: caps as barycentric grids of `n`
/// steps per side, walls with `levels` rows; outward (the prism is convex).
SurfaceMesh make_prism(const std::array<Vec3, 3>& c, double h, int n, int levels) {
  SurfaceMesh m;
  std::map<std::array<int, 4>, Index> index;  // (i, j, level, wall-or-cap id) keys shared vertices
  const auto vertex = [&](int i, int j, int level) {
    const int k = n - i - j;
    const bool border = i == 0 || j == 0 || k == 0;
    const std::array<int, 4> key{i, j, border ? level : (level == 0 ? 0 : levels), 0};
    auto [it, inserted] = index.try_emplace(key, static_cast<Index>(m.vertices.size()));
    if (inserted) {
      const Vec3 xy = (i * c[0] + j * c[1] + k * c[2]) / n;
      m.vertices.emplace_back(xy.x(), xy.y(), -h + 2 * h * key[2] / levels);
    }
    return it->second;
  };
  for (int level : {0, levels})
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        m.faces.push_back({vertex(i, j, level), vertex(i + 1, j, level), vertex(i, j + 1, level)});
        if (i + j + 1 < n) m.faces.push_back({vertex(i + 1, j, level), vertex(i + 1, j + 1, level), vertex(i, j + 1, level)});
      }
  // The border of the cap grid, in order: (i, j) steps along c2→c0 (j = 0), c0→c1, c1→c2.
  std::vector<std::array<int, 2>> ring;
  for (int s = 0; s < n; ++s) ring.push_back({s, 0});
  for (int s = 0; s < n; ++s) ring.push_back({n - s, s});
  for (int s = 0; s < n; ++s) ring.push_back({0, n - s});
  for (std::size_t r = 0; r < ring.size(); ++r) {
    const auto& a = ring[r];
    const auto& b = ring[(r + 1) % ring.size()];
    for (int level = 0; level < levels; ++level) {
      m.faces.push_back({vertex(a[0], a[1], level), vertex(b[0], b[1], level), vertex(b[0], b[1], level + 1)});
      m.faces.push_back({vertex(a[0], a[1], level), vertex(b[0], b[1], level + 1), vertex(a[0], a[1], level + 1)});
    }
  }
  const Vec3 centre = (c[0] + c[1] + c[2]) / 3;
  for (Tri& f : m.faces) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &d = m.vertices[f[2]];
    if ((b - a).cross(d - a).dot((a + b + d) / 3 - centre) < 0) std::swap(f[1], f[2]);
  }
  return m;
}

/// Every triangle faces away from the bases of its corners (exact orientation test).
std::size_t inconsistent_triangles(const RefinedPrimitive& r) {
  std::size_t bad = 0;
  for (const Tri& f : r.mesh.faces)
    for (Index corner : f)
      bad += CGAL::orientation(point(r.mesh.vertices[f[0]]), point(r.mesh.vertices[f[1]]), point(r.mesh.vertices[f[2]]),
                               point(r.base[corner])) != CGAL::NEGATIVE;
  return bad;
}

/// The refined mesh's triangles, in S's vertex ids where every corner is an S vertex.
std::set<std::array<Index, 3>> input_triangles(const RefinedPrimitive& r) {
  std::set<std::array<Index, 3>> result;
  for (const Tri& f : r.mesh.faces) {
    Tri t{r.input_vertex[f[0]], r.input_vertex[f[1]], r.input_vertex[f[2]]};
    if (t[0] == kNotInput || t[1] == kNotInput || t[2] == kNotInput) continue;
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    result.insert(t);
  }
  return result;
}

std::array<Index, 3> rotated(Tri t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

/// The invariants of every refined primitive: closed, 2-manifold, outward, consistent, and S's
/// vertices and triangles of its patch present exactly.
void check_refined(const RefinedPrimitive& r, const TargetMesh& target) {
  INFO(r.note);
  REQUIRE(r.refined);
  REQUIRE(r.base.size() == r.mesh.vertices.size());
  REQUIRE(r.input_vertex.size() == r.mesh.vertices.size());
  check_closed_manifold(r.mesh.faces, r.mesh.vertices.size());
  CHECK(inconsistent_triangles(r) == 0);
  double volume = 0;
  for (const Tri& f : r.mesh.faces) volume += r.mesh.vertices[f[0]].dot(r.mesh.vertices[f[1]].cross(r.mesh.vertices[f[2]]));
  CHECK(volume > 0);
  // Input vertices sit exactly on S's vertices.
  for (std::size_t v = 0; v < r.mesh.vertices.size(); ++v)
    if (r.input_vertex[v] != kNotInput) REQUIRE(r.mesh.vertices[v] == target.mesh().vertices[r.input_vertex[v]]);
  // Every S triangle of the patch is a triangle of the mesh (so its vertices and edges are too).
  const std::set<std::array<Index, 3>> present = input_triangles(r);
  REQUIRE(!r.input_faces.empty());
  for (Index f : r.input_faces) REQUIRE(present.count(rotated(target.mesh().faces[f])) == 1);
  // The patch is the selection, less a few border triangles, plus a few filling small holes.
  std::vector<Index> taken;
  std::set_intersection(r.selected_faces.begin(), r.selected_faces.end(), r.input_faces.begin(), r.input_faces.end(),
                        std::back_inserter(taken));
  CHECK(taken.size() >= 0.8 * static_cast<double>(r.selected_faces.size()));
  CHECK(r.input_faces.size() - taken.size() <= 0.1 * static_cast<double>(r.selected_faces.size()));
}

/// One primitive covering all of S comes back as S: the same vertices and triangles.
void check_exactly_s(const RefinedPrimitive& r, const TargetMesh& target) {
  check_refined(r, target);
  const SurfaceMesh& s = target.mesh();
  CHECK(r.mesh.vertices.size() == s.vertices.size());
  CHECK(r.mesh.faces.size() == s.faces.size());
  std::set<std::array<Index, 3>> expected;
  for (const Tri& f : s.faces) expected.insert(rotated(f));
  CHECK(input_triangles(r) == expected);
}

}  // namespace

TEST_CASE("msd refinement: a box covered by one vertex primitive comes back exactly as the box") {
  const TargetMesh box(testing::make_box(0.5, 0.4, 0.3, 3));
  const Primitive p = fit_primitive(box, vertex_at({0.02, -0.01, 0.01}));
  REQUIRE(p.fitted);
  const RefinedPrimitive r = refine_primitive(p, box);
  CHECK(r.selected_vertices.size() == box.mesh().vertices.size());
  check_exactly_s(r, box);
}

TEST_CASE("msd refinement: a closed cylinder covered by one edge primitive comes back exactly") {
  const TargetMesh cylinder(testing::make_cylinder(0.3, 0.6, 16));
  const Primitive p = fit_primitive(cylinder, edge_between({0, 0, -0.3}, {0, 0, 0.3}));
  REQUIRE(p.fitted);
  check_exactly_s(refine_primitive(p, cylinder), cylinder);
}

TEST_CASE("msd refinement: a triangular prism covered by one triangle primitive comes back exactly") {
  const std::array<Vec3, 3> section{Vec3(1, 0, 0), Vec3(-0.5, 0.866, 0), Vec3(-0.5, -0.866, 0)};
  const TargetMesh prism(make_prism(section, 0.25, 4, 2));
  const std::array<Vec3, 3> inner{section[0] * 0.5, section[1] * 0.5, section[2] * 0.5};
  const Primitive p = fit_primitive(prism, {ElementKind::Triangle, {0, 1, 2}, inner});
  REQUIRE(p.fitted);
  check_exactly_s(refine_primitive(p, prism), prism);
}

TEST_CASE("msd refinement: two vertex primitives in a long capsule each take over the end they cover exactly") {
  // The primitives grow to at most 3.5 ρ0 (25 raises of 10 %): each covers one end of the
  // capsule, neither the middle.
  const TargetMesh capsule(testing::make_capsule(0.3, 1.5, 24));
  const std::vector<Primitive> primitives{fit_primitive(capsule, vertex_at({0, 0, -1.2})),
                                          fit_primitive(capsule, vertex_at({0.01, 0, 1.2}))};
  const std::vector<RefinedPrimitive> refined = refine_primitives(primitives, capsule);
  // Selection: each primitive selects the tip of its own end and nothing past the middle.
  for (int k = 0; k < 2; ++k) {
    const double side = k == 0 ? -1 : 1;
    const std::vector<Index>& selected = refined[k].selected_vertices;
    const auto is_selected = [&](Index v) { return std::binary_search(selected.begin(), selected.end(), v); };
    std::size_t tips = 0, wrong_side = 0;
    for (Index v = 0; v < capsule.mesh().vertices.size(); ++v) {
      const double z = side * capsule.mesh().vertices[v].z();
      if (z > 1.7) tips += !is_selected(v);
      if (z < 0) wrong_side += is_selected(v);
    }
    CHECK(tips == 0);
    CHECK(wrong_side == 0);
  }
  for (const RefinedPrimitive& r : refined) {
    check_refined(r, capsule);
    // A partial cover: the patch is part of S, and the rest of the template is kept.
    CHECK(r.input_faces.size() < capsule.mesh().faces.size() / 2);
    CHECK(std::count(r.input_vertex.begin(), r.input_vertex.end(), kNotInput) > 0);
  }
}

TEST_CASE("msd refinement: an unfitted primitive is returned empty and unrefined") {
  const TargetMesh sphere(testing::make_sphere(1.0, 2));
  Primitive p;
  p.element = vertex_at(Vec3::Zero());
  const RefinedPrimitive r = refine_primitive(p, sphere);
  CHECK_FALSE(r.refined);
  CHECK(r.mesh.faces.empty());
  CHECK(!r.note.empty());
}

TEST_CASE("msd refinement: the result does not depend on the thread count") {
  const TargetMesh box(testing::make_box(0.8, 0.4, 0.4, 6));
  const std::vector<Primitive> primitives{fit_primitive(box, vertex_at({-0.4, 0, 0})),
                                          fit_primitive(box, vertex_at({0.4, 0.02, 0})),
                                          fit_primitive(box, edge_between({-0.3, 0, 0}, {0.3, 0, 0}))};
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return refine_primitives(primitives, box);
  };
  const std::vector<RefinedPrimitive> one = run(1), two = run(2);
  REQUIRE(one.size() == two.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    CHECK(one[k].refined == two[k].refined);
    CHECK(one[k].mesh.vertices == two[k].mesh.vertices);
    CHECK(one[k].mesh.faces == two[k].mesh.faces);
    CHECK(one[k].input_faces == two[k].input_faces);
  }
}
