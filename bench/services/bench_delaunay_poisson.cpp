// The two costs every Voronoi method pays at scale (issue 16), on koala.obj:
// - poisson/<n>: Poisson-disk sampling of n points by count (the `sample` stage), seed 1;
// - poisson_darts/<n>: the same from candidates thinned by dart throwing (`candidates: darts`);
// - delaunay/<n>/threads:<t>: the shared Delaunay service on n cached Poisson samples, with t
//   TBB threads (tbb::global_control).
// Targets (issue 16, Release, 2 cores): Poisson 1M <= 5 s (met by poisson_darts), Delaunay 1M <= 5 s.
//
//   build-bench/bin/bench_delaunay_poisson [--benchmark_filter=1M] [--meshes DIR]
//
// The poisson line ends with a hash of the samples (points, normals, areas): run the same binary
// against another libmedax_services.so (LD_LIBRARY_PATH) to check that a change keeps them.
//
// 100k runs are repeated and the fastest is kept, 1M runs once (the machine is shared); the CPU
// column is the process's CPU time (all threads), which a loaded machine inflates less than the
// wall time.
#include "common/koala_samples.hpp"
#include "common/thread_cpu.hpp"

#include <medax/services/delaunay.hpp>
#include <medax/services/poisson.hpp>
#include <medax/services/sampling.hpp>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <cstdint>

namespace {

using namespace medax;
using Clock = std::chrono::steady_clock;

std::filesystem::path meshes_dir = MEDAX_CORPUS_DIR;

/// Fastest of the repetitions: wall time, process CPU time, and the busiest thread's CPU time
/// (what the run would take on an idle machine, see common/thread_cpu.hpp).
struct Timing {
  double wall = 1e300, cpu = 1e300, busiest = 1e300;
  template <typename F>
  void measure(F&& run) {
    const auto threads0 = bench::thread_cpu_seconds();
    const std::clock_t cpu0 = std::clock();
    const auto t0 = Clock::now();
    run();
    wall = std::min(wall, std::chrono::duration<double>(Clock::now() - t0).count());
    cpu = std::min(cpu, static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC);
    busiest = std::min(busiest, bench::busiest_thread_seconds(threads0, bench::thread_cpu_seconds()));
  }
  void report(benchmark::State& state) const {
    state.counters["s_wall"] = wall;
    state.counters["s_cpu"] = cpu;
    state.counters["s_busiest_thread"] = busiest;
  }
};

/// FNV-1a over the bytes of the samples' points, normals and areas.
std::uint64_t samples_hash(const OrientedSamples& s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  const auto mix = [&h](const void* data, std::size_t bytes) {
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 0x100000001b3ull;
  };
  mix(s.points.data(), s.points.size() * sizeof(Vec3));
  mix(s.normals.data(), s.normals.size() * sizeof(Vec3));
  mix(s.areas.data(), s.areas.size() * sizeof(double));
  return h;
}

/// The benchmark's name for the elimination's candidates.
const char* name(services::PoissonCandidates candidates) {
  return candidates == services::PoissonCandidates::Uniform ? "poisson" : "poisson_darts";
}

std::string tag(std::size_t n) { return n >= 1000000 ? std::to_string(n / 1000000) + "M" : std::to_string(n / 1000) + "k"; }

void BM_Poisson(benchmark::State& state, std::size_t n, int threads, services::PoissonCandidates candidates) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const SurfaceMesh& mesh = bench::koala(meshes_dir);
  Timing time;
  double min_distance = 0;
  std::uint64_t hash = 0;
  for (auto _ : state) {
    std::mt19937_64 rng(1);
    OrientedSamples s;
    services::PoissonDiskOptions options;
    options.candidates = candidates;
    time.measure([&] { s = services::sample_poisson_count(mesh, n, rng, options); });
    state.PauseTiming();
    min_distance = services::min_sample_distance(s) / services::poisson_packing_distance(services::surface_area(mesh), n);
    hash = samples_hash(s);
    state.ResumeTiming();
  }
  time.report(state);
  state.counters["min_dist/packing"] = min_distance;
  std::printf("%s/%s/threads:%d: wall %.3f s, cpu %.3f s, busiest thread %.3f s (target 1M <= 5 s); "
              "minimum distance %.3f of the hexagonal packing's; samples hash %016llx\n",
              name(candidates), tag(n).c_str(), threads, time.wall, time.cpu, time.busiest, min_distance,
              static_cast<unsigned long long>(hash));
}

void BM_Delaunay(benchmark::State& state, std::size_t n, int threads) {
  const OrientedSamples& s = bench::koala_samples(meshes_dir, n);
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Timing time;
  std::size_t cells = 0;
  for (auto _ : state) {
    time.measure([&] {
      const auto dt = services::delaunay_tetrahedralize(s.points);
      cells = dt.cells.size();
    });
  }
  time.report(state);
  std::printf("delaunay/%s/threads:%d: wall %.3f s, cpu %.3f s, busiest thread %.3f s (%.2f us/pt), %zu cells "
              "(target 1M <= 5 s on 2 cores)\n",
              tag(n).c_str(), threads, time.wall, time.cpu, time.busiest, 1e6 * time.busiest / static_cast<double>(n),
              cells);
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--meshes") == 0) meshes_dir = argv[i + 1];
  if (!std::filesystem::exists(meshes_dir / "koala.obj")) {
    std::fprintf(stderr, "koala.obj not found in %s (scripts/fetch-meshes.sh, or --meshes DIR)\n", meshes_dir.c_str());
    return 1;
  }
  for (std::size_t n : {std::size_t{100000}, std::size_t{1000000}}) {
    const int reps = n >= 1000000 ? 1 : 3;
    for (int threads : {1, 2}) {
      const std::string suffix = tag(n) + "/threads:" + std::to_string(threads);
      for (const auto candidates : {services::PoissonCandidates::Uniform, services::PoissonCandidates::Darts})
        benchmark::RegisterBenchmark((std::string(name(candidates)) + "/" + suffix).c_str(), BM_Poisson, n, threads,
                                     candidates)
            ->Unit(benchmark::kSecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(reps);
      benchmark::RegisterBenchmark(("delaunay/" + suffix).c_str(), BM_Delaunay, n, threads)
          ->Unit(benchmark::kSecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(reps);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
