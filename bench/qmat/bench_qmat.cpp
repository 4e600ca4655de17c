// Q-MAT simplification time (the paper's "Q-MAT simp" column of VMAS Table 2): the interior
// Voronoi axis of the mesh vertices is built once per model (not timed), then simplified to the
// Table 1 sphere count with the default options. Counters: input and output vertex counts.
#include "collapse.hpp"
#include "interior_voronoi.hpp"

#include <medax/io.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>

using namespace medax;

namespace {

struct Model {
  const char* file;
  std::size_t spheres;
  double paper_seconds;  ///< VMAS Table 2, "Q-MAT simp"
};
const Model kModels[] = {
    {"armadillo.off", 83, 10.3}, {"fertility.off", 98, 4.6}, {"elephant.off", 117, 6.6}, {"plane.obj", 86, 1.5}};

struct Input {
  MedialComplex axis;
  double diagonal = 1;
};

const Input& voronoi_input(const std::string& file) {
  static std::map<std::string, Input> cache;
  auto it = cache.find(file);
  if (it != cache.end()) return it->second;
  const SurfaceMesh mesh = read_mesh(std::filesystem::path(MEDAX_CORPUS_DIR) / file);
  Input in{voronoi::interior_voronoi(mesh.vertices, mesh), bbox_diagonal(mesh.vertices)};
  return cache.emplace(file, std::move(in)).first->second;
}

void BM_QmatSimplify(benchmark::State& state) {
  const Model& m = kModels[state.range(0)];
  const Input& in = voronoi_input(m.file);
  qmat::QmatOptions o;
  o.target_vertices = m.spheres;
  o.unit_length = in.diagonal;
  std::size_t out = 0;
  for (auto _ : state) {
    const MedialComplex result = qmat::simplify(in.axis, {}, o);
    out = result.num_vertices();
    benchmark::DoNotOptimize(out);
  }
  state.SetLabel(m.file);
  state.counters["input_vertices"] = static_cast<double>(in.axis.num_vertices());
  state.counters["output_vertices"] = static_cast<double>(out);
  state.counters["paper_s"] = m.paper_seconds;  // beside this run's time per iteration
}
BENCHMARK(BM_QmatSimplify)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
