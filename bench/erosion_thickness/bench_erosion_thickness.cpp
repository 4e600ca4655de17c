// Erosion Thickness benchmarks (Google Benchmark, build Release).
//
// The medial complex: the interior Voronoi complex of 4 of every 7 vertices of armadillo.off
// (about 15k surface points), cleaned by pure_complex: about 50k vertices, the size of the
// paper's Dolphin ("under just a few seconds [...] with 50K vertices", 3.2 GHz quad-core,
// omega = 0.004). Target here: ET (graph + Burn) under 1 s at omega = 0.004 of the max bbox side.
//
//   BM_ErosionThickness/<1/omega>: graph construction + Burn (what the `erosion_thickness`
//       stage computes), for omega = 1/250 ... ; counters: graph nodes and arcs.
//   BM_Burn: Burn alone at omega = 0.004 (graph built once).
//   BM_MedialCurves, BM_Skeleton: the rest of the paper's pipeline at omega = 0.004, from a
//       ready burn (subdivision + curves with ET_C; subdivision + skeleton at the defaults).
//
// Run: build/bench/erosion_thickness/bench_erosion_thickness [--benchmark_filter=...]
#include "erosion_thickness.hpp"
#include "pure_complex.hpp"
#include "voronoi_fixture.hpp"
#ifdef MEDAX_ET_HAVE_VORONOI
#include "interior_voronoi.hpp"
#endif

#include <medax/io.hpp>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

using namespace medax;
using namespace medax::et;

namespace {

struct Input {
  MedialComplex complex;
  double length = 1;  ///< max bbox side of the mesh
};

const Input& input() {
  static const std::unique_ptr<Input> in = [] {
    auto data = std::make_unique<Input>();
    const SurfaceMesh mesh = read_mesh(std::string(MEDAX_CORPUS_DIR) + "/armadillo.off");
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
      if (i % 7 < 4) points.push_back(mesh.vertices[i]);
#ifdef MEDAX_ET_HAVE_VORONOI
    data->complex = voronoi::interior_voronoi(points, mesh);  // the `voronoi` plugin's algorithm
#else
    data->complex = testing::interior_voronoi_complex(points, mesh);  // its test stand-in
#endif
    make_pure_complex(data->complex, 1e-9);
    Vec3 lo = mesh.vertices[0], hi = lo;
    for (const Vec3& p : mesh.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    data->length = (hi - lo).maxCoeff();
    std::fprintf(stderr, "armadillo (%zu of %zu vertices): medial complex with %zu vertices, %zu triangles\n",
                 points.size(), mesh.vertices.size(), data->complex.num_vertices(), data->complex.faces.size());
    return data;
  }();
  return *in;
}

void BM_ErosionThickness(benchmark::State& state) {
  const Input& in = input();
  const double omega = in.length / double(state.range(0));
  std::size_t nodes = 0, arcs = 0;
  for (auto _ : state) {
    const auto run = run_erosion_thickness(in.complex, omega, 1);
    benchmark::DoNotOptimize(run->burn.bt.data());
    nodes = run->graph.num_nodes();
    state.PauseTiming();
    arcs = run->graph.count_arcs();
    state.ResumeTiming();
  }
  state.counters["omega"] = 1.0 / double(state.range(0));
  state.counters["complex_vertices"] = double(in.complex.num_vertices());
  state.counters["nodes"] = double(nodes);
  state.counters["arcs"] = double(arcs);
  state.SetLabel("paper: under a few seconds at 50k vertices, omega 0.004 (3.2 GHz quad-core)");
}
BENCHMARK(BM_ErosionThickness)->Arg(125)->Arg(250)->Arg(500)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_Burn(benchmark::State& state) {
  const Input& in = input();
  const auto run = run_erosion_thickness(in.complex, 0.004 * in.length, 1);
  for (auto _ : state) {
    const BurnResult r = burn(run->graph);
    benchmark::DoNotOptimize(r.bt.data());
  }
  state.counters["pops"] = double(run->burn.pops);
  state.counters["relaxations"] = double(run->burn.relaxations);
}
BENCHMARK(BM_Burn)->Unit(benchmark::kMillisecond);

void BM_MedialCurves(benchmark::State& state) {
  const Input& in = input();
  const auto run = run_erosion_thickness(in.complex, 0.004 * in.length, 1);
  std::size_t vertices = 0;
  for (auto _ : state) {
    const Subdivision sub = build_subdivision(run->graph, run->burn);
    const MedialCurves c = extract_medial_curves(run->graph, sub);
    vertices = c.points.size();
  }
  state.counters["curve_vertices"] = double(vertices);
}
BENCHMARK(BM_MedialCurves)->Unit(benchmark::kMillisecond);

void BM_Skeleton(benchmark::State& state) {
  const Input& in = input();
  const auto run = run_erosion_thickness(in.complex, 0.004 * in.length, 1);
  SkeletonOptions o;
  o.theta2 = 0.02 * in.length;
  o.theta1 = 0.04 * in.length;
  o.phi2 = 0.0005 * in.length * in.length;
  std::size_t refined = 0, faces = 0;
  Skeleton last;
  for (auto _ : state) {
    const Subdivision sub = build_subdivision(run->graph, run->burn);
    const Skeleton sk = compute_skeleton(run->graph, sub, run->loose_edges, o);
    refined = sk.refined_faces;
    last.seconds_refine = sk.seconds_refine;
    last.seconds_protect = sk.seconds_protect;
    last.seconds_contract = sk.seconds_contract;
    last.seconds_output = sk.seconds_output;
    faces = sk.faces.size();
  }
  state.counters["wedges"] = double(refined);
  state.counters["skeleton_triangles"] = double(faces);
  state.counters["s_cells"] = last.seconds_refine;
  state.counters["s_protect"] = last.seconds_protect;
  state.counters["s_collapse"] = last.seconds_contract - last.seconds_protect;
  state.counters["s_output"] = last.seconds_output;
}
BENCHMARK(BM_Skeleton)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
