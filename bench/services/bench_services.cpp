// Inside tests, surface distances and envelope distances on armadillo (26k vertices):
// 100k query points spread over the bounding box, the load of voronoi's and reconstruction's
// inner loops.
#include <medax/io.hpp>
#include <medax/services/closest_point.hpp>
#include <medax/services/envelope.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/ray_parity.hpp>

#include "interior_voronoi.hpp"

#include <benchmark/benchmark.h>

#include <random>

namespace {

using namespace medax;

const SurfaceMesh& armadillo() {
  static const SurfaceMesh mesh = read_mesh(std::filesystem::path(MEDAX_CORPUS_DIR) / "armadillo.off");
  return mesh;
}

/// 100k points, uniform in the mesh's bounding box, fixed seed.
const std::vector<Vec3>& queries() {
  static const std::vector<Vec3> points = [] {
    Vec3 lo = armadillo().vertices[0], hi = lo;
    for (const Vec3& v : armadillo().vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    std::mt19937_64 rng(7);
    std::vector<Vec3> out(100000);
    for (Vec3& p : out)
      for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return out;
  }();
  return points;
}

void BM_InsideTestSideOfMesh(benchmark::State& state) {
  for (auto _ : state) {
    const services::InsideTest test(armadillo());
    benchmark::DoNotOptimize(test.inside(queries()));
  }
}

void BM_InsideTestRayParity(benchmark::State& state) {
  for (auto _ : state) {
    const services::RayParityInside test(armadillo());
    benchmark::DoNotOptimize(test.inside(queries()));
  }
}

void BM_SurfaceDistance(benchmark::State& state) {
  for (auto _ : state) {
    const services::SurfaceDistance distance(armadillo());
    benchmark::DoNotOptimize(distance.distances(queries()));
  }
}

void BM_EnvelopeDistance(benchmark::State& state) {
  static const MedialComplex medial = voronoi::interior_voronoi(armadillo().vertices, armadillo());
  for (auto _ : state) {
    const services::Envelope envelope(medial);
    benchmark::DoNotOptimize(envelope.signed_distances(queries()));
  }
}

}  // namespace

BENCHMARK(BM_InsideTestSideOfMesh)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_InsideTestRayParity)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SurfaceDistance)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EnvelopeDistance)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
