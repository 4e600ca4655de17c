// VMAS timings: whole runs at the paper's Table 1 sphere counts (models normalised to the unit
// box, λ = 0.2, connectivity included), by thread count; and the phases of the loop on
// armadillo at 83 spheres (partition, update, correction, precompute, an edit with its local
// relaxation). Times are wall-clock; the counters give the sphere count and iterations.
#include "energy.hpp"
#include "partition.hpp"
#include "update.hpp"
#include "vmas.hpp"

#include <medax/io.hpp>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <filesystem>
#include <map>
#include <memory>

using namespace medax;
using namespace medax::vmas;

namespace {

struct Model {
  const char* file;
  std::size_t spheres;
};
const Model kModels[] = {{"armadillo.off", 83}, {"fertility.off", 98}, {"elephant.off", 117}, {"plane.obj", 86}};

const SurfaceMesh& unit_box_mesh(const std::string& file) {
  static std::map<std::string, SurfaceMesh> cache;
  auto it = cache.find(file);
  if (it != cache.end()) return it->second;
  SurfaceMesh mesh = read_mesh(std::filesystem::path(MEDAX_CORPUS_DIR) / file);
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (const Vec3& p : mesh.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double s = (hi - lo).maxCoeff();
  for (Vec3& p : mesh.vertices) p = (p - lo) / s;
  return cache.emplace(file, std::move(mesh)).first->second;
}

/// Runs `body` with at most `threads` TBB threads.
template <typename F>
void with_threads(int threads, F&& body) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  arena.execute(body);
}

/// A converged armadillo at 83 spheres, shared by the phase benchmarks, run with `scope`.
const VmasSolver& armadillo_83(UpdateScope scope = UpdateScope::Local) {
  static std::map<UpdateScope, VmasSolver> solvers;
  auto it = solvers.find(scope);
  if (it != solvers.end()) return it->second;
  VmasOptions o;
  o.target_spheres = 83;
  o.update_scope = scope;
  VmasSolver s(VmasInput::from_mesh(unit_box_mesh("armadillo.off")), o);
  s.run();
  s.finish();
  return solvers.emplace(scope, std::move(s)).first->second;
}

// Whole run, as Table 2's "Ours": precompute + optimisation + connectivity. Args: model, threads.
void BM_Table1(benchmark::State& state) {
  const Model& m = kModels[state.range(0)];
  const SurfaceMesh& mesh = unit_box_mesh(m.file);
  const int threads = static_cast<int>(state.range(1));
  std::size_t spheres = 0;
  int iterations = 0;
  for (auto _ : state) {
    with_threads(threads, [&] {
      VmasOptions o;
      o.target_spheres = m.spheres;
      VmasSolver s(VmasInput::from_mesh(mesh), o);
      s.run();
      s.finish();
      const MedialComplex mc = s.complex(true);
      benchmark::DoNotOptimize(mc.faces.data());
      spheres = s.size();
      iterations = s.iterations();
    });
  }
  state.SetLabel(std::string(m.file) + " @" + std::to_string(m.spheres) +
                 " (paper, Table 2 \"Ours\": 0.34-2.58 s per model, i7-12700K)");
  state.counters["spheres"] = static_cast<double>(spheres);
  state.counters["iterations"] = iterations;
  state.counters["vertices"] = static_cast<double>(mesh.vertices.size());
}
BENCHMARK(BM_Table1)->ArgsProduct({{0, 1, 2, 3}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_Precompute(benchmark::State& state) {
  const SurfaceMesh& mesh = unit_box_mesh("armadillo.off");
  for (auto _ : state)
    with_threads(static_cast<int>(state.range(0)), [&] { benchmark::DoNotOptimize(VmasInput::from_mesh(mesh).get()); });
}
BENCHMARK(BM_Precompute)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Partition(benchmark::State& state) {
  const VmasSolver& s = armadillo_83();
  std::vector<Sphere> spheres;
  for (const SphereInfo& i : s.spheres()) spheres.push_back({i.centre - s.input().origin, i.radius});
  std::vector<int> cluster_of;
  const bool hinted = state.range(1) != 0;  // the previous partition as the pruning hint, as the solver does
  for (auto _ : state)
    with_threads(static_cast<int>(state.range(0)), [&] {
      assign_vertices(s.input(), spheres, 0.2, cluster_of, hinted ? &s.assignment() : nullptr);
    });
  state.SetLabel(hinted ? "hinted" : "no hint");
  state.counters["evaluations/s"] = benchmark::Counter(static_cast<double>(s.input().size() * spheres.size()),
                                                       benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Partition)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// One Gauss-Newton update of every sphere (and, with range(1), the correction).
void BM_Update(benchmark::State& state) {
  const VmasSolver& s = armadillo_83();
  std::vector<Sphere> spheres;
  for (const SphereInfo& i : s.spheres()) spheres.push_back({i.centre - s.input().origin, i.radius});
  const Clusters clusters = group_clusters(s.assignment(), spheres.size());
  const bool correct = state.range(1) != 0;
  for (auto _ : state)
    with_threads(static_cast<int>(state.range(0)), [&] {
      tbb::parallel_for(std::size_t{0}, spheres.size(), [&](std::size_t i) {
        Sphere r = update_sphere(s.input(), clusters.begin(i), clusters.size(i), spheres[i], {}).sphere;
        if (correct) r = s.input().correct(r);
        benchmark::DoNotOptimize(r.radius);
      });
    });
  state.SetLabel(correct ? "update + correction" : "update");
}
BENCHMARK(BM_Update)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The interactive edit: split the sphere with the largest error, then 10 iterations without splits.
// Args: threads, update scope (0 local, 1 full).
void BM_EditSplitRelax(benchmark::State& state) {
  const bool full = state.range(1) != 0;
  for (auto _ : state) {
    state.PauseTiming();
    VmasSolver s = armadillo_83(full ? UpdateScope::Full : UpdateScope::Local);
    SphereId worst = 0;
    double e = -1;
    for (const SphereInfo& i : s.spheres())
      if (i.error > e) e = i.error, worst = i.id;
    state.ResumeTiming();
    with_threads(static_cast<int>(state.range(0)), [&] {
      s.split_sphere(worst);
      for (int k = 0; k < 10; ++k) s.relax();
    });
  }
  state.SetLabel(full ? "full update" : "local update");
}
BENCHMARK(BM_EditSplitRelax)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
