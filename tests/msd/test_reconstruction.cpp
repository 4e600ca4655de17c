// Ŝ = ∪ T_P by the signed-distance grid (plugins/msd/reconstruction): a sphere primitive gives a
// sphere within a voxel; a union of primitives is one closed 2-manifold holding every base point;
// the same surface with 1 or 2 threads; a failed primitive has no surface.
#include "mesh_checks.hpp"
#include "primitive_template.hpp"
#include "reconstruction.hpp"

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <cmath>

using namespace medax;
using namespace medax::msd;
using medax::msd::checks::check_closed_manifold;
using medax::msd::checks::winding;

namespace {

/// T_P at constant radius ρ: the medial primitive (sphere, capsule, slab) of the element.
Primitive constant_primitive(const SkeletonElement& element, double rho, std::size_t sphere_vertices) {
  Primitive p;
  p.element = element;
  p.shape = make_template(element, rho, TemplateOptions{sphere_vertices, 200});
  p.initial_radius = rho;
  p.radius.assign(p.shape.size(), rho);
  p.max_radius = p.radius;
  p.fitted = true;
  return p;
}

/// A ball, a capsule leaving it and a slab at the capsule's far end: connected, genus 0.
std::vector<Primitive> three_primitives() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(1.5, 0.8, 0.1), d(1.8, -0.3, 0);
  return {constant_primitive({ElementKind::Vertex, {0, 0, 0}, {a, a, a}}, 0.3, 400),
          constant_primitive({ElementKind::Edge, {0, 1, 0}, {a, b, b}}, 0.2, 400),
          constant_primitive({ElementKind::Triangle, {1, 2, 3}, {b, c, d}}, 0.15, 400)};
}

}  // namespace

TEST_CASE("msd Ŝ of one sphere primitive is the sphere of radius ρ within a voxel") {
  const Vec3 centre(0.2, -0.1, 0.3);
  const double rho = 0.25;
  const std::vector<Primitive> sphere{constant_primitive({ElementKind::Vertex, {0, 0, 0}, {centre, centre, centre}},
                                                         rho, 1588)};
  const SdfOptions options;  // the paper's 256 voxels across
  const double voxel = sdf_voxel_size(fitted_surfaces(sphere), options);
  CHECK(voxel == Approx(2 * rho / 256).epsilon(0.01));
  const ReconstructedSurface rebuilt = reconstruct_sdf(fitted_surfaces(sphere), Similarity{}, options);
  const SurfaceMesh& mesh = rebuilt.surface;
  REQUIRE(mesh.faces.size() > 1000);
  double worst = 0;
  for (const Vec3& x : mesh.vertices) worst = std::max(worst, std::abs((x - centre).norm() - rho));
  CHECK(worst < voxel);
  check_closed_manifold(mesh.faces, mesh.vertices.size());
  CHECK(winding(mesh.vertices, mesh.faces, centre) == Approx(1.0).margin(1e-6));  // outward
}

TEST_CASE("msd Ŝ of a ball, a capsule and a slab is one closed 2-manifold holding every base point") {
  std::vector<Primitive> primitives = three_primitives();
  primitives.push_back(primitives.front());
  primitives.back().fitted = false;  // a failed primitive is left out
  const std::vector<SurfaceMesh> solids = fitted_surfaces(primitives);
  REQUIRE(solids.size() == 3);
  const ReconstructedSurface rebuilt = reconstruct_sdf(solids, Similarity{}, SdfOptions{64});
  const SurfaceMesh& mesh = rebuilt.surface;
  check_closed_manifold(mesh.faces, mesh.vertices.size());
  std::size_t outside = 0, tested = 0;
  for (const Primitive& p : primitives)
    for (std::size_t i = 0; i < p.shape.size(); i += 7, ++tested)
      outside += winding(mesh.vertices, mesh.faces, p.shape.base[i]) < 0.5;
  CHECK(tested > 50);
  CHECK(outside == 0);
  CHECK_THROWS_WITH(reconstruct_sdf({}, Similarity{}), Catch::Contains("no primitive surface"));
}

TEST_CASE("msd Ŝ is the same surface with 1 or 2 threads") {
  const std::vector<SurfaceMesh> solids = fitted_surfaces(three_primitives());
  const auto rebuild = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return reconstruct_sdf(solids, Similarity{}, SdfOptions{96}).surface;
  };
  const SurfaceMesh one = rebuild(1), two = rebuild(2);
  CHECK(one.vertices == two.vertices);
  CHECK(one.faces == two.faces);
}
