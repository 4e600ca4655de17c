// Interior Voronoi extraction vs the bare Delaunay tetrahedralization of the same points.
//
//   build-bench/bin/bench_voronoi [--benchmark_filter=armadillo] [--meshes DIR]
//
// "Time" is wall-clock, "CPU" the CPU time of all the process's threads (both use threads);
// each benchmark is repeated 5 times and the minimum is kept, the figure least disturbed by
// other load on the machine. After the runs, one line per mesh gives the ratio
// voronoi / delaunay of those minima, wall and CPU; the target is a wall ratio of at most 1.5.
// `paired/<mesh>` alternates the two 15 times (both under the same load) and reports the
// minima, their ratio and the median of the per-round ratios: the steadiest figure on a busy
// machine.
#include <medax/io.hpp>
#include <medax/services/delaunay.hpp>

#include "interior_voronoi.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>

namespace {

using namespace medax;

std::filesystem::path meshes_dir = MEDAX_CORPUS_DIR;

const SurfaceMesh& mesh(const std::string& file) {
  static std::map<std::string, SurfaceMesh> cache;
  auto it = cache.find(file);
  if (it == cache.end()) it = cache.emplace(file, read_mesh(meshes_dir / file)).first;
  return it->second;
}

void BM_Delaunay(benchmark::State& state, const std::string& file) {
  const SurfaceMesh& m = mesh(file);
  std::size_t cells = 0;
  for (auto _ : state) {
    const auto dt = services::delaunay_tetrahedralize(m.vertices);
    cells = dt.cells.size();
    benchmark::DoNotOptimize(dt.cells.data());
  }
  state.counters["points"] = static_cast<double>(m.vertices.size());
  state.counters["cells"] = static_cast<double>(cells);
}

void BM_Voronoi(benchmark::State& state, const std::string& file, voronoi::InsideMethod inside) {
  const SurfaceMesh& m = mesh(file);
  voronoi::InteriorVoronoiOptions options;
  options.inside = inside;
  voronoi::InteriorVoronoiReport report, sum;
  std::size_t vertices = 0, faces = 0;
  for (auto _ : state) {
    const MedialComplex medial = voronoi::interior_voronoi(m.vertices, m, options, &report);
    vertices = medial.num_vertices();
    faces = medial.faces.size();
    sum.seconds_delaunay += report.seconds_delaunay;
    sum.seconds_inside += report.seconds_inside;
    sum.seconds_complex += report.seconds_complex;
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["s_delaunay"] = sum.seconds_delaunay / runs;
  state.counters["s_inside"] = sum.seconds_inside / runs;
  state.counters["s_complex"] = sum.seconds_complex / runs;
}

/// Delaunay and voronoi alternately on the same mesh, `rounds` times each, so that both see the
/// same load; reports the minimum of each, their ratio, and the median of the per-round ratios.
void BM_Paired(benchmark::State& state, const std::string& file) {
  const SurfaceMesh& m = mesh(file);
  using Clock = std::chrono::steady_clock;
  std::vector<double> delaunay, voronoi_s, ratios;
  for (auto _ : state) {
    auto t0 = Clock::now();
    const auto dt = services::delaunay_tetrahedralize(m.vertices);
    benchmark::DoNotOptimize(dt.cells.data());
    auto t1 = Clock::now();
    const MedialComplex medial = voronoi::interior_voronoi(m.vertices, m);
    benchmark::DoNotOptimize(medial.centres.data());
    auto t2 = Clock::now();
    delaunay.push_back(std::chrono::duration<double>(t1 - t0).count());
    voronoi_s.push_back(std::chrono::duration<double>(t2 - t1).count());
    ratios.push_back(voronoi_s.back() / delaunay.back());
  }
  std::sort(ratios.begin(), ratios.end());
  const double d = *std::min_element(delaunay.begin(), delaunay.end());
  const double v = *std::min_element(voronoi_s.begin(), voronoi_s.end());
  state.counters["s_delaunay_min"] = d;
  state.counters["s_voronoi_min"] = v;
  state.counters["ratio_of_min"] = v / d;
  state.counters["ratio_median"] = ratios[ratios.size() / 2];
}

/// Console output plus, at the end, the voronoi / delaunay ratio of every mesh (minimum over
/// the repetitions of each), for wall-clock time and for the CPU time of all threads.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  RatioReporter() : ConsoleReporter(OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs)  // the fastest repetition: the least disturbed by other load
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "min")
        times_[run.run_name.function_name] = {run.GetAdjustedRealTime() / 1e3, run.GetAdjustedCPUTime() / 1e3};
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    for (const auto& [name, t] : times_) {
      if (name.rfind("voronoi/", 0) != 0) continue;
      const std::string rest = name.substr(std::string("voronoi/").size());
      const auto dt = times_.find("delaunay/" + rest.substr(0, rest.find('/')));
      if (dt == times_.end()) continue;
      std::printf("ratio %-32s wall %.3f s / %.3f s = %.2f   cpu %.3f s / %.3f s = %.2f\n", name.c_str(), t.first,
                  dt->second.first, t.first / dt->second.first, t.second, dt->second.second,
                  t.second / dt->second.second);
    }
  }

 private:
  std::map<std::string, std::pair<double, double>> times_;  // wall, cpu (s)
};

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--meshes") == 0) meshes_dir = argv[i + 1];
  for (const std::string file : {"armadillo.off", "koala.obj"}) {
    if (!std::filesystem::exists(meshes_dir / file)) {
      std::cerr << "skipping " << file << ": not found in " << meshes_dir << "\n";
      continue;
    }
    const std::string stem = std::filesystem::path(file).stem().string();
    const auto setup = [](benchmark::internal::Benchmark* b) {
      b->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(0.5)->Repetitions(5)->ComputeStatistics(
          "min", [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); });
    };
    setup(benchmark::RegisterBenchmark(("delaunay/" + stem).c_str(), BM_Delaunay, file));
    setup(benchmark::RegisterBenchmark(("voronoi/" + stem).c_str(), BM_Voronoi, file, voronoi::InsideMethod::RayGrid));
    setup(benchmark::RegisterBenchmark(("voronoi/" + stem + "/side_of_mesh").c_str(), BM_Voronoi, file,
                                       voronoi::InsideMethod::SideOfMesh));
    benchmark::RegisterBenchmark(("paired/" + stem).c_str(), BM_Paired, file)
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(15);
  }
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
}
