// Benchmark: the evaluation stages on the interior-Voronoi complex of a mesh (default:
// data/meshes/armadillo.off of the corpus, scripts/fetch-meshes.sh). Usage: bench_evaluation [MESH] [REPEATS]
//
// `bench_evaluation --accuracy` instead prints the error of the envelope boundary sampling on
// envelopes with a known answer (the table in docs/plugins/evaluation.md).
#include "counts.hpp"
#include "reconstruction.hpp"
#include "interior_voronoi.hpp"

#include <medax/io.hpp>
#include <medax/services/envelope.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/services/topology.hpp>

#include <chrono>
#include <sys/resource.h>
#include <functional>
#include <random>
#include <cstdio>
#include <string>

using namespace medax;

namespace {
/// User + system CPU time of the process: with other work on the machine, wall time says little;
/// CPU time / cores is what an idle machine would take.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

constexpr double kPi = 3.14159265358979323846;

double simpson(const std::function<double(double)>& f, double a, double b, int n = 200000) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
  return sum * h / 3;
}

/// Sampling error on two envelopes with exact answers: a sphere (radius 0.7) and a capsule
/// (ρ = 0.3, L = 0.7, two spheres and a cone) measured against the exact unit sphere, at steps
/// 2/resolution (2 = the smallest side of the unit sphere's box, as the VMAS rule).
int accuracy() {
  std::printf("| envelope | resolution | step | samples | area error | covering radius / step | "
              "max error | mean error |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  std::mt19937_64 rng(1);
  const auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  const auto direction = [&] {
    Vec3 d;
    do d = Vec3(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1);
    while (d.squaredNorm() > 1 || d.squaredNorm() < 1e-6);
    return Vec3(d.normalized());
  };
  for (const bool capsule : {false, true}) {
    const double rho = capsule ? 0.3 : 0.7, half = capsule ? 0.7 : 0.0;
    MedialComplex mc;
    mc.add_vertex({0, 0, -half}, rho);
    if (capsule) {
      mc.add_vertex({0, 0, half}, rho);
      mc.add_edge(0, 1);
    }
    const double area = 4 * kPi * rho * rho + 4 * kPi * rho * half;
    // Distance to the unit sphere: |1 − |q||; exact max and area mean.
    const double exact_max = capsule ? 1 - rho : 1 - rho;
    const double exact_mean =
        capsule ? (simpson([&](double z) { return std::abs(1 - std::sqrt(rho * rho + z * z)) * 2 * kPi * rho; }, -half,
                           half) +
                   2 * simpson(
                           [&](double t) {
                             return std::abs(1 - std::sqrt(half * half + rho * rho + 2 * half * rho * t)) * 2 * kPi *
                                    rho * rho;
                           },
                           0.0, 1.0)) /
                      area
                : 1 - rho;
    const services::Envelope envelope(mc);
    for (const int resolution : {50, 150, 300}) {
      const double step = 2.0 / resolution;
      const services::EnvelopeSamples s = envelope.sample_boundary(step);
      double mx = 0, weighted = 0;
      for (std::size_t i = 0; i < s.size(); ++i) {
        const double d = std::abs(1 - s.points[i].norm());
        mx = std::max(mx, d);
        weighted += s.areas[i] * d;
      }
      // Covering radius: the farthest of 20000 random exact boundary points from the samples.
      const services::PointIndex index(s.points);
      double cover = 0;
      for (int i = 0; i < 20000; ++i) {
        const Vec3 u = direction();
        Vec3 p;
        if (capsule && uniform() * area < 4 * kPi * rho * half) {
          p = rho * Vec3(u.x(), u.y(), 0).normalized() + Vec3(0, 0, (2 * uniform() - 1) * half);
        } else {
          p = rho * u + Vec3(0, 0, u.z() >= 0 ? half : -half);
        }
        cover = std::max(cover, index.nearest(p).second);
      }
      std::printf("| %s | %d | %.4f | %zu | %+.3f%% | %.2f | %.2e | %+.2e (%+.3f%%) |\n",
                  capsule ? "capsule vs unit sphere" : "sphere r=0.7 vs unit sphere", resolution, step, s.size(),
                  100 * (s.total_area() / area - 1), cover / step, exact_max - mx, weighted / s.total_area() - exact_mean,
                  100 * (weighted / s.total_area() / exact_mean - 1));
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--accuracy") return accuracy();
  const std::string path = argc > 1 ? argv[1] : std::string(MEDAX_SOURCE_DIR "/data/meshes/armadillo.off");
  const int repeats = argc > 2 ? std::stoi(argv[2]) : 3;
  Shape shape;
  shape.mesh = read_mesh(path);
  std::printf("mesh %s: %zu vertices, %zu faces\n", path.c_str(), shape.mesh.vertices.size(), shape.mesh.faces.size());

  auto t0 = std::chrono::steady_clock::now();
  const MedialComplex mc = voronoi::interior_voronoi(shape.mesh.vertices, shape.mesh);
  std::printf("interior Voronoi complex: %zu vertices, %zu edges, %zu faces (%.2f s)\n", mc.num_vertices(),
              mc.edges.size(), mc.faces.size(), seconds_since(t0));

  for (int r = 0; r < repeats; ++r) {
    std::mt19937_64 rng(0);
    const double cpu0 = cpu_seconds();
    t0 = std::chrono::steady_clock::now();
    auto last = t0;
    std::string phases;
    const auto result = evaluation::measure_reconstruction(
        shape, mc, {}, rng, [&](double, std::string_view what) {
          const auto now = std::chrono::steady_clock::now();
          if (!phases.empty() && phases.back() != '|') {
            phases += " " + std::to_string(std::chrono::duration<double>(now - last).count()).substr(0, 5) + "s | ";
          }
          if (what != "done") phases += std::string(what);
          last = now;
        });
    const double total = seconds_since(t0);
    std::printf("reconstruction: %.3f s wall, %.3f s CPU  [%s]\n", total, cpu_seconds() - cpu0, phases.c_str());
    if (r == 0) {
      for (const auto& [name, value] : result.metrics()) std::printf("  %-32s %.6g\n", name.c_str(), value);
    }
  }
  t0 = std::chrono::steady_clock::now();
  const auto counts = evaluation::count_elements(mc);
  std::printf("counts: %.3f s (N_d %zu)\n", seconds_since(t0), counts.discrete());
  t0 = std::chrono::steady_clock::now();
  const auto topo = services::complex_topology(mc);
  std::printf("topology (complex): %.3f s  chi %lld b0 %zu b1 %zu b2 %zu\n", seconds_since(t0), topo.euler, topo.b0,
              topo.b1, topo.b2);
  t0 = std::chrono::steady_clock::now();
  const auto st = services::surface_topology(shape.mesh);
  std::printf("topology (surface): %.3f s  chi %lld genus %g\n", seconds_since(t0), st.complex.euler, st.genus());
  return 0;
}
