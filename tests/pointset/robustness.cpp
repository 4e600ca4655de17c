// The robustness experiment of issue 17 (not a ctest; docs/pointclouds.md): shared meshes sampled
// at several densities, with Gaussian noise of 0.1–2 % of the diagonal or a patch cut out, the
// normals dropped, then cleaned (jet smoothing when noisy; jet normals, MST orientation) and given
// to voronoi (normals inside test), dey_zhao (normals inner selection) and vmas (point-cloud mode).
// Each result is compared with the same method's on the clean mesh: error = mean of the two
// one-sided mean nearest-centre distances and 95th percentile of the cloud→mesh one, in % of the
// diagonal (with the two-sided median, which ignores far spikes); topology = b0, b1 of the complex. One CSV row per run on stdout.
//
//   build/tests/pointcloud_robustness /work/shared/data/meshes > robustness.csv
#include "clouds.hpp"

#include "interior_voronoi.hpp"
#include "medial.hpp"
#include "point_processing.hpp"
#include "vmas.hpp"

#include <medax/io.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/services/sampling.hpp>
#include <medax/services/topology.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <iostream>
#include <map>

using namespace medax;

namespace {

constexpr std::size_t kSpheres = 50;

/// The mesh centred and scaled to a unit bounding-box diagonal.
SurfaceMesh unit_mesh(const std::filesystem::path& file) {
  SurfaceMesh mesh = read_mesh(file);
  Vec3 lo = mesh.vertices[0], hi = lo;
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double diagonal = (hi - lo).norm();
  for (Vec3& v : mesh.vertices) v = (v - 0.5 * (lo + hi)) / diagonal;
  return mesh;
}

MedialComplex run_voronoi(const OrientedSamples& cloud) { return voronoi::interior_voronoi(cloud); }

MedialComplex run_dey_zhao(const OrientedSamples& cloud, const SurfaceMesh* mesh) {
  dey_zhao::MedialInput input;
  input.points = &cloud.points;
  input.normals = &cloud.normals;
  input.mesh = mesh;
  dey_zhao::MedialOptions options;
  options.inner = mesh ? dey_zhao::InnerSelection::Mesh : dey_zhao::InnerSelection::Normals;
  return dey_zhao::medial_axis(input, options);
}

MedialComplex run_vmas(std::shared_ptr<const vmas::VmasInput> input) {
  vmas::VmasOptions options;
  options.target_spheres = kSpheres;
  vmas::VmasSolver solver(std::move(input), options);
  solver.run();
  solver.finish();
  return solver.complex(true);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

std::vector<double> nearest_distances(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  const services::PointIndex index(to);
  std::vector<double> d;
  d.reserve(from.size());
  for (const Vec3& p : from) d.push_back(index.nearest(p).second);
  return d;
}

struct Comparison {
  double chamfer = 0, median = 0, p95 = 0;
};

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

Comparison compare(const MedialComplex& cloud, const MedialComplex& reference) {
  const std::vector<double> forward = nearest_distances(cloud.centres, reference.centres);
  const std::vector<double> backward = nearest_distances(reference.centres, cloud.centres);
  Comparison c;
  c.chamfer = 100 * 0.5 * (mean(forward) + mean(backward));
  c.median = 100 * 0.5 * (quantile(forward, 0.5) + quantile(backward, 0.5));
  c.p95 = 100 * quantile(forward, 0.95);
  return c;
}

/// A cloud as a scan gives it: uniform samples, normals dropped, noise or a hole; then cleaned.
OrientedSamples scan(const SurfaceMesh& mesh, std::size_t n, double noise, bool hole, unsigned seed) {
  std::mt19937_64 rng(seed);
  OrientedSamples cloud = services::sample_uniform(mesh, n, rng);
  if (hole) test::cut_patch(cloud, cloud.points[0], 0.05);  // 5 % of the (unit) diagonal
  cloud.normals.clear();
  if (noise > 0) {
    test::add_noise(cloud, noise, seed + 1);
    pointset::jet_smooth(cloud, 24);
  }
  pointset::estimate_and_orient_normals(cloud, true, {});
  return cloud;
}

struct Reference {
  MedialComplex complex;
  services::ComplexTopology topology;
};

void row(const std::string& mesh, std::size_t n, double noise, bool hole, const std::string& method,
         const std::function<MedialComplex()>& extract, const Reference& reference) {
  std::string line = fmt::format("{},{},{},{},{},", mesh, n, noise * 100, hole ? 1 : 0, method);
  try {
    const MedialComplex m = extract();
    const services::ComplexTopology t = services::complex_topology(m);
    const Comparison c = compare(m, reference.complex);
    line += fmt::format("{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},ok", m.num_vertices(), m.faces.size(), t.b0, t.b1,
                        reference.topology.b0, reference.topology.b1, c.chamfer, c.median, c.p95);
  } catch (const std::exception& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), ',', ';');
    line += fmt::format(",,,,{},{},,,,failed: {}", reference.topology.b0, reference.topology.b1, what);
  }
  std::cout << line << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path dir = argc > 1 ? argv[1] : "/work/shared/data/meshes";
  std::cout << "mesh,points,noise_pct,hole,method,vertices,faces,b0,b1,ref_b0,ref_b1,chamfer_pct,median_pct,p95_pct,status\n";
  for (const std::string name : {"spot.obj", "torus.obj", "fertility.off"}) {
    const SurfaceMesh mesh = unit_mesh(dir / name);
    for (const std::size_t n : {4000, 16000}) {
      std::mt19937_64 rng(1);
      const OrientedSamples clean = services::sample_uniform(mesh, n, rng);
      std::map<std::string, Reference> reference;
      const auto add = [&](const std::string& method, MedialComplex m) {
        reference[method] = {m, services::complex_topology(m)};
      };
      add("voronoi", voronoi::interior_voronoi(clean.points, mesh));
      add("dey_zhao", run_dey_zhao(clean, &mesh));
      add("vmas", run_vmas(vmas::VmasInput::from_mesh(mesh)));
      for (const double noise : {0.0, 0.001, 0.005, 0.01, 0.02})
        for (const bool hole : {false, true}) {
          if (hole && noise > 0) continue;
          OrientedSamples cloud;
          try {
            cloud = scan(mesh, n, noise, hole, 7);
          } catch (const std::exception& e) {
            std::cout << fmt::format("{},{},{},{},all,,,,,,,,,,failed: {}\n", name, n, noise * 100, hole ? 1 : 0, e.what());
            continue;
          }
          row(name, n, noise, hole, "voronoi", [&] { return run_voronoi(cloud); }, reference["voronoi"]);
          row(name, n, noise, hole, "dey_zhao", [&] { return run_dey_zhao(cloud, nullptr); }, reference["dey_zhao"]);
          row(name, n, noise, hole, "vmas", [&] { return run_vmas(vmas::VmasInput::from_samples(cloud)); },
              reference["vmas"]);
        }
    }
  }
}
