// Ŝ without a grid (plugins/msd/union_surface): two overlapping spheres give the analytic union
// within the meshes' chord error and keep nothing inside the other sphere; boxes on one grid give
// the union exactly (area, no vertex inside the other box); shared faces are kept once, faces
// where two solids touch are dropped; a surface within the tolerance of another is kept; the same
// surface with 1 or 2 threads; with refined
// primitives covering all of S, Ŝ holds every vertex of S exactly (ε̄¹ = 0) and the refinement
// does not raise ε̄.
#include "fitting.hpp"
#include "mesh_checks.hpp"
#include "reconstruction.hpp"
#include "refinement.hpp"
#include "union_surface.hpp"

#include <medax/io.hpp>
#include <medax/services/closest_point.hpp>
#include <medax/services/sampling.hpp>

#include "../support/test_paths.hpp"

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <map>

using namespace medax;
using namespace medax::msd;
using medax::msd::checks::check_closed_manifold;

namespace {

/// The unit sphere of tests/data (642 vertices, radius 1 to 1e-6), moved to `centre`.
SurfaceMesh unit_sphere(const Vec3& centre) {
  SurfaceMesh mesh = read_mesh(medax::test::data_dir() / "sphere.obj");
  for (Vec3& v : mesh.vertices) v += centre;
  return mesh;
}

/// The box [low, high] with every face a grid of squares of side `step` (two triangles each),
/// closed and outward oriented, so boxes on one lattice share vertices and triangles.
SurfaceMesh box_mesh(const Vec3& low, const Vec3& high, double step) {
  const Eigen::Array3i cells = ((high - low) / step).array().round().cast<int>();
  SurfaceMesh mesh;
  std::map<std::array<int, 3>, Index> index;
  const auto vertex = [&](const std::array<int, 3>& g) {
    const auto [it, added] = index.emplace(g, static_cast<Index>(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(low + step * Vec3(g[0], g[1], g[2]));
    return it->second;
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;  // e_b × e_c = e_a
      for (int i = 0; i < cells[b]; ++i)
        for (int j = 0; j < cells[c]; ++j) {
          std::array<Index, 4> q;
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> g{};
            g[a] = side * cells[a];
            g[b] = i + di[k];
            g[c] = j + dj[k];
            q[k] = vertex(g);
          }
          if (side == 1) {
            mesh.faces.push_back({q[0], q[1], q[2]});
            mesh.faces.push_back({q[0], q[2], q[3]});
          } else {
            mesh.faces.push_back({q[0], q[2], q[1]});
            mesh.faces.push_back({q[0], q[3], q[2]});
          }
        }
    }
  return mesh;
}

bool strictly_inside(const Vec3& x, const Vec3& low, const Vec3& high) {
  return (x.array() > low.array() + 1e-12).all() && (x.array() < high.array() - 1e-12).all();
}

}  // namespace

TEST_CASE("msd union Ŝ of two overlapping spheres is their analytic union within the chord error") {
  const Vec3 a(0, 0, 0), b(1, 0, 0);  // radius 1, centres 1 apart
  const SurfaceMesh one = unit_sphere(a), two = unit_sphere(b);
  const ReconstructedSurface rebuilt = reconstruct_union({one, two}, Similarity{}, UnionOptions{1e-9});
  const SurfaceMesh& mesh = rebuilt.surface;
  CHECK_THAT(rebuilt.method, Catch::Contains("without a grid"));
  REQUIRE(mesh.faces.size() > 1000);
  // Every vertex on the boundary of the union: min(|x − a|, |x − b|) = 1 within the chord error.
  double worst = 0;
  for (const Vec3& x : mesh.vertices) worst = std::max(worst, std::abs(std::min((x - a).norm(), (x - b).norm()) - 1));
  CHECK(worst < 5e-3);
  // Nothing inside the other sphere is kept: a triangle's centroid is at most the chord error deep
  // (a whole triangle inside would be up to 1 deep).
  double deepest = 0;
  for (const Tri& f : mesh.faces) {
    const Vec3 c = (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3;
    deepest = std::max(deepest, 1 - std::max((c - a).norm(), (c - b).norm()));
  }
  CHECK(deepest < 5e-3);
  // Area: two spheres minus a cap of height 1/2 each, 2·(4π − π) = 6π, scaled by the mesh's own
  // area deficit against 4π.
  const double deficit = services::surface_area(one) / (4 * M_PI);
  CHECK(services::surface_area(mesh) == Approx(6 * M_PI * deficit).epsilon(5e-3));
}

TEST_CASE("msd union Ŝ of two boxes on one grid is their union exactly") {
  const Vec3 low_a(0, 0, 0), high_a(1, 1, 1), low_b(0.5, 0.25, 0.25), high_b(1.5, 0.75, 0.75);
  const SurfaceMesh mesh =
      reconstruct_union({box_mesh(low_a, high_a, 0.125), box_mesh(low_b, high_b, 0.125)}, Similarity{}).surface;
  // Area 6 + 2.5 − 0.25 (A's face inside B) − 1.25 (B's faces inside A).
  CHECK(services::surface_area(mesh) == Approx(7.0).epsilon(1e-12));
  std::size_t inside = 0;
  for (const Vec3& x : mesh.vertices) inside += strictly_inside(x, low_a, high_a) || strictly_inside(x, low_b, high_b);
  CHECK(inside == 0);
}

TEST_CASE("msd union Ŝ keeps triangles two solids share once and drops faces where two solids touch") {
  const SurfaceMesh a = box_mesh({0, 0, 0}, {1, 1, 1}, 0.25);
  SECTION("a box inside another sharing five faces' triangles: the outer box, each triangle once") {
    const SurfaceMesh mesh = reconstruct_union({a, box_mesh({0, 0, 0}, {0.5, 1, 1}, 0.25)}, Similarity{}).surface;
    CHECK(mesh.faces.size() == a.faces.size());
    CHECK(services::surface_area(mesh) == Approx(6.0).epsilon(1e-12));
    check_closed_manifold(mesh.faces, mesh.vertices.size());
  }
  SECTION("two boxes face to face: the interface goes, the 2×1×1 box remains, closed") {
    const SurfaceMesh mesh = reconstruct_union({a, box_mesh({1, 0, 0}, {2, 1, 1}, 0.25)}, Similarity{}).surface;
    CHECK(services::surface_area(mesh) == Approx(10.0).epsilon(1e-12));
    check_closed_manifold(mesh.faces, mesh.vertices.size());
  }
  CHECK_THROWS_WITH(reconstruct_union({SurfaceMesh{}}, Similarity{}), Catch::Contains("no primitive surface"));
}

TEST_CASE("msd union Ŝ keeps a surface within the tolerance of another, and drops it when deeper") {
  // The unit sphere inside a copy 5e-4 larger: with the default tolerance (1e-3) it is on the
  // larger one and both layers stay; judged to 1e-9 it is inside and only the larger one stays.
  const SurfaceMesh inner = unit_sphere({0, 0, 0});
  SurfaceMesh outer = inner;
  for (Vec3& v : outer.vertices) v *= 1.0005;
  CHECK(reconstruct_union({inner, outer}, Similarity{}).surface.faces.size() == 2 * inner.faces.size());
  const SurfaceMesh strict = reconstruct_union({inner, outer}, Similarity{}, UnionOptions{1e-9}).surface;
  CHECK(strict.faces.size() == outer.faces.size());
  CHECK(services::surface_area(strict) == Approx(services::surface_area(outer)).epsilon(1e-12));
}

TEST_CASE("msd union Ŝ is the same surface with 1 or 2 threads") {
  const std::vector<SurfaceMesh> solids{unit_sphere({0, 0, 0}), unit_sphere({0.7, 0.4, 0}), unit_sphere({0, 1, 0.5})};
  const auto rebuild = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return reconstruct_union(solids, Similarity{}).surface;
  };
  const SurfaceMesh one = rebuild(1), two = rebuild(2);
  CHECK(one.vertices == two.vertices);
  CHECK(one.faces == two.faces);
}

TEST_CASE("msd union Ŝ of refined primitives covering all of S holds every vertex of S exactly") {
  // Two vertex primitives inside the unit sphere each grow to all of it; refined, each is S itself.
  const SurfaceMesh sphere = unit_sphere({0, 0, 0});
  const TargetMesh target(sphere);
  FitOptions fit;
  fit.templates.sphere_vertices = 400;
  std::vector<Primitive> primitives;
  for (const Vec3& c : {Vec3(-0.3, 0, 0), Vec3(0.3, 0.1, 0)})
    primitives.push_back(fit_primitive(target, {ElementKind::Vertex, {0, 0, 0}, {c, c, c}}, fit));
  for (const Primitive& p : primitives) REQUIRE(p.fitted);
  const std::vector<RefinedPrimitive> refined = refine_primitives(primitives, target);
  for (const RefinedPrimitive& r : refined) CHECK(r.refined);
  const SurfaceMesh fitted_union = reconstruct_union(fitted_surfaces(primitives), Similarity{}).surface;
  const SurfaceMesh refined_union = reconstruct_union(refined_surfaces(refined), Similarity{}).surface;
  const double eps1 = checks::mean_distance(sphere.vertices, refined_union);
  CHECK(eps1 < 1e-15);  // ε̄¹ = 0 to rounding
  const auto eps = [&](const SurfaceMesh& rebuilt) { return checks::two_sided_error(sphere, rebuilt); };
  CHECK(eps(fitted_union) > 1e-4);  // the fitted T_P cut corners between S's vertices
  CHECK(eps(refined_union) <= eps(fitted_union));
  // The two refined copies of S's triangles are one: Ŝ is S, closed.
  CHECK(refined_union.faces.size() == sphere.faces.size());
  check_closed_manifold(refined_union.faces, refined_union.vertices.size());
}
