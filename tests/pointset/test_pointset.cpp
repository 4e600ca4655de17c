// The pointset package on analytic clouds: normals estimated or re-oriented against the exact
// ones, outliers removed, noise smoothed, simplification, reconstruction, and the errors.
#include "clouds.hpp"

#include "point_processing.hpp"
#include "reconstruction.hpp"
#include "stages.hpp"

#include <catch2/catch.hpp>

using namespace medax;
using namespace medax::pointset;
using medax::test::ellipsoid_cloud;
using medax::test::torus_cloud;

namespace {

struct Named {
  const char* name;
  OrientedSamples cloud;
};

std::vector<Named> analytic_clouds() {
  return {{"sphere", ellipsoid_cloud(1, 1, 1, 2000, 1)},
          {"ellipsoid", ellipsoid_cloud(1.5, 1.0, 0.6, 3000, 2)},
          {"torus", torus_cloud(1.0, 0.35, 4000, 3)}};
}

/// Share of the points whose normal is within `degrees` of the exact one (same orientation).
double agreeing(const OrientedSamples& cloud, const std::vector<Vec3>& exact, double degrees) {
  std::size_t good = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) good += cloud.normals[i].dot(exact[i]) > std::cos(degrees * M_PI / 180);
  return static_cast<double>(good) / static_cast<double>(cloud.size());
}

double rms_sphere_error(const OrientedSamples& cloud) {
  double sum = 0;
  for (const Vec3& p : cloud.points) sum += (p.norm() - 1) * (p.norm() - 1);
  return std::sqrt(sum / static_cast<double>(cloud.size()));
}

}  // namespace

TEST_CASE("normals flipped at random are re-oriented outward", "[pointset][normals]") {
  for (Named& shape : analytic_clouds()) {
    INFO(shape.name);
    const std::vector<Vec3> exact = shape.cloud.normals;
    medax::test::flip_at_random(shape.cloud, 11);
    REQUIRE(agreeing(shape.cloud, exact, 1) < 0.6);
    const NormalReport report = estimate_and_orient_normals(shape.cloud, false, {});
    CHECK_FALSE(report.estimated);
    CHECK(report.dropped == 0);
    CHECK(report.flipped > shape.cloud.size() / 3);
    CHECK(agreeing(shape.cloud, exact, 0.01) == 1.0);  // every sign restored, directions untouched
  }
}

TEST_CASE("a cloud without normals gets outward normals close to the exact ones", "[pointset][normals]") {
  for (const NormalMethod method : {NormalMethod::Jet, NormalMethod::Pca})
    for (Named& shape : analytic_clouds()) {
      INFO(shape.name << (method == NormalMethod::Jet ? " jet" : " pca"));
      const std::vector<Vec3> exact = shape.cloud.normals;
      shape.cloud.normals.clear();
      NormalOptions options;
      options.method = method;
      const NormalReport report = estimate_and_orient_normals(shape.cloud, true, options);
      REQUIRE(report.dropped == 0);
      REQUIRE(shape.cloud.normals.size() == exact.size());
      CHECK(agreeing(shape.cloud, exact, 90) == 1.0);  // all outward
      CHECK(agreeing(shape.cloud, exact, 10) > 0.98);
    }
}

TEST_CASE("clouds too small or too flat are refused with what to do", "[pointset][errors]") {
  OrientedSamples small = ellipsoid_cloud(1, 1, 1, 10, 4);
  small.normals.clear();
  CHECK_THROWS_WITH(estimate_and_orient_normals(small, true, {}),
                    Catch::Contains("normal estimation with 18 neighbours needs at least 19 points but the cloud has "
                                    "10") &&
                        Catch::Contains("lower `k`"));
  OrientedSamples flat;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) flat.points.emplace_back(i, j, 0.0);
  CHECK_THROWS_WITH(estimate_and_orient_normals(flat, true, {}), Catch::Contains("the cloud is flat"));
  CHECK_THROWS_WITH(remove_outliers(flat, {}), Catch::Contains("lie on a plane"));
}

TEST_CASE("far points are removed as outliers and the surface is kept", "[pointset][outliers]") {
  OrientedSamples cloud = ellipsoid_cloud(1, 1, 1, 3000, 5);
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> box(-2, 2);
  std::size_t far = 0;
  while (far < 30) {
    const Vec3 p(box(rng), box(rng), box(rng));
    if (std::abs(p.norm() - 1) < 0.3) continue;
    cloud.points.push_back(p);
    cloud.normals.push_back(Vec3::UnitZ());
    ++far;
  }
  const std::size_t removed = remove_outliers(cloud, {});
  CHECK(removed >= 30);
  CHECK(removed < 30 + 30);  // under 1 % of the surface points
  for (const Vec3& p : cloud.points) CHECK(std::abs(p.norm() - 1) < 0.3);
  CHECK(cloud.normals.size() == cloud.size());
}

TEST_CASE("jet smoothing brings noisy points back towards the surface", "[pointset][smooth]") {
  OrientedSamples cloud = ellipsoid_cloud(1, 1, 1, 3000, 7);
  medax::test::add_noise(cloud, 0.01, 8);
  const double before = rms_sphere_error(cloud);
  jet_smooth(cloud, 24);
  CHECK(rms_sphere_error(cloud) < 0.5 * before);
}

TEST_CASE("grid and WLOP simplification thin the cloud", "[pointset][simplify]") {
  OrientedSamples grid = ellipsoid_cloud(1, 1, 1, 3000, 9);
  SimplifyOptions options;
  options.cell = 0.05;
  const std::size_t removed = simplify(grid, options);
  CHECK(removed > 1000);
  CHECK(grid.normals.size() == grid.size());
  double total = 0;
  for (double a : grid.areas) total += a;
  CHECK(total == Approx(4 * M_PI).epsilon(0.25));
  OrientedSamples wlop = ellipsoid_cloud(1, 1, 1, 2000, 10);
  options.method = SimplifyMethod::Wlop;
  simplify(wlop, options);
  CHECK(wlop.size() == Approx(400).margin(2));
  CHECK(wlop.normals.empty());
  CHECK(rms_sphere_error(wlop) < 0.02);
}

TEST_CASE("Poisson reconstruction of a sphere cloud is a closed sphere", "[pointset][reconstruct]") {
  const OrientedSamples cloud = ellipsoid_cloud(1, 1, 1, 3000, 12);
  ReconstructionReport report;
  const SurfaceMesh mesh = reconstruct_surface(cloud, {}, &report);
  CHECK(report.border_edges == 0);
  REQUIRE(mesh.faces.size() > 300);
  double worst = 0;
  for (const Vec3& v : mesh.vertices) worst = std::max(worst, std::abs(v.norm() - 1));
  CHECK(worst < 0.03);
  OrientedSamples bare = cloud;
  bare.normals.clear();
  CHECK_THROWS_WITH(reconstruct_surface(bare, {}), Catch::Contains("needs oriented normals"));
}

TEST_CASE("advancing-front reconstruction triangulates the points themselves", "[pointset][reconstruct]") {
  OrientedSamples cloud = ellipsoid_cloud(1, 1, 1, 2000, 13);
  cloud.normals.clear();
  ReconstructionOptions options;
  options.method = ReconstructionMethod::AdvancingFront;
  ReconstructionReport report;
  const SurfaceMesh mesh = reconstruct_surface(cloud, options, &report);
  CHECK(mesh.vertices == cloud.points);
  CHECK(mesh.faces.size() > 3500);  // a closed triangulation of 2000 points has 3996
  CHECK(report.border_edges < 20);
}

TEST_CASE("the stages refuse a shape without points and say which stage makes what", "[pointset][stages]") {
  Scene scene;
  scene.shape.mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  scene.shape.mesh.faces = {{0, 1, 2}};
  NormalsStage normals;
  CHECK_THROWS_WITH(normals.prepare(scene), Catch::Contains("the shape has no points"));
  scene.shape.samples = ellipsoid_cloud(1, 1, 1, 500, 14);
  scene.shape.samples.normals.clear();
  ReconstructMeshStage reconstruct;
  CHECK_THROWS_WITH(reconstruct.prepare(scene), Catch::Contains("put a `normals` stage before this one"));
  CHECK(normals.makes() == std::vector<ShapePart>{ShapePart::Samples});
}
