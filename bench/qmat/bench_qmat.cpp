// Q-MAT simplification time (the paper's "Q-MAT simp" column of VMAS Table 2): the interior
// Voronoi axis of the mesh vertices is built once per model (not timed), then simplified to the
// Table 1 sphere count with the default options, on one thread (/0) or on all (/1: the parts
// that run in parallel, with the same result). Time is wall clock, CPU that of the whole
// process. Counters: input and output vertex counts, the wall seconds of two phases per
// simplification (`setup_s`: collapse mesh, initial quadrics, first costing; `loop_s`: the
// collapses; the rest is the output complex), and `identical` = 1 when the fingerprint of the
// simplified complex (every bit of its spheres, its edges and faces, also in the label) is the
// reference one: that of commit a5e66e1's code built with GCC 12 -O3 on x86-64, so a speed-up
// can be checked to change nothing.
#include "collapse.hpp"
#include "interior_voronoi.hpp"

#include <medax/io.hpp>

#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>

#include <tbb/global_control.h>

using namespace medax;

namespace {

struct Model {
  const char* file;
  std::size_t spheres;
  double paper_seconds;    ///< VMAS Table 2, "Q-MAT simp"
  std::uint64_t reference;  ///< fingerprint of the result (see above)
};
const Model kModels[] = {{"armadillo.off", 83, 10.3, 0xd432047f0084c79f},
                         {"fertility.off", 98, 4.6, 0x897aeda60727766c},
                         {"elephant.off", 117, 6.6, 0x84af3326b0d08928},
                         {"plane.obj", 86, 1.5, 0x3c2c57bc13d37807}};

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

/// FNV-1a over the bytes of the complex's centres, radii, edges and faces.
std::uint64_t fingerprint(const MedialComplex& m) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) h = (h ^ p[k]) * 1099511628211ull;
  };
  for (const Vec3& c : m.centres) mix(c.data(), 3 * sizeof(double));
  mix(m.radii.data(), m.radii.size() * sizeof(double));
  mix(m.edges.data(), m.edges.size() * sizeof(Segment));
  mix(m.faces.data(), m.faces.size() * sizeof(Tri));
  return h;
}

void BM_QmatSimplify(benchmark::State& state) {
  const Model& m = kModels[state.range(0)];
  const Input& in = voronoi_input(m.file);
  qmat::QmatOptions o;
  o.target_vertices = m.spheres;
  o.unit_length = in.diagonal;
  std::optional<tbb::global_control> one_thread;
  if (state.range(1) == 0) one_thread.emplace(tbb::global_control::max_allowed_parallelism, 1);
  std::size_t out = 0;
  std::uint64_t print = 0;
  double setup = 0, loop = 0;
  for (auto _ : state) {
    qmat::QmatReport report;
    const MedialComplex result = qmat::simplify(in.axis, {}, o, &report);
    setup += report.seconds_setup;
    loop += report.seconds_collapse;
    out = result.num_vertices();
    print = fingerprint(result);
    benchmark::DoNotOptimize(out);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(print));
  state.SetLabel(std::string(m.file) + " " + hex);
  state.counters["input_vertices"] = static_cast<double>(in.axis.num_vertices());
  state.counters["output_vertices"] = static_cast<double>(out);
  state.counters["paper_s"] = m.paper_seconds;  // beside this run's time per iteration
  state.counters["setup_s"] = benchmark::Counter(setup, benchmark::Counter::kAvgIterations);
  state.counters["loop_s"] = benchmark::Counter(loop, benchmark::Counter::kAvgIterations);
  state.counters["identical"] = print == m.reference ? 1 : 0;
}
BENCHMARK(BM_QmatSimplify)
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
