// Runs delaunay_surface + durix on meshes and prints one Markdown row per mesh, with the
// invariants checked on the result (not a ctest: real meshes take seconds each).
//
//   durix_real_meshes [--eps 0.01] [MESH_OR_FOLDER ...]   (default: ../shared/data/meshes)
#include "delaunay_mesh.hpp"
#include "durix.hpp"

#include <medax/io.hpp>
#include <medax/services/mesh_check.hpp>
#include <medax/services/topology.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace medax;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool is_mesh(const fs::path& p) {
  const std::string e = p.extension().string();
  return e == ".off" || e == ".obj" || e == ".ply" || e == ".stl";
}

void run_one(const fs::path& path, double eps) {
  std::string name = path.filename().string();
  SurfaceMesh mesh;
  try {
    mesh = read_mesh(path);
  } catch (const std::exception& e) {
    std::printf("| %s | read failed: %s |\n", name.c_str(), e.what());
    return;
  }
  auto t0 = std::chrono::steady_clock::now();
  services::MeshCheckOptions check_options;
  const services::MeshReport check = services::check_mesh(mesh, check_options);
  const double t_check = seconds_since(t0);
  if (!check.ok()) {
    std::printf("| %s | %zu | refused by delaunay_surface: %s |\n", name.c_str(), mesh.vertices.size(),
                check.describe_problems().c_str());
    std::fflush(stdout);
    return;
  }
  const long long genus_in = check.genus ? *check.genus : -1;
  durix::DelaunayMeshReport conv;
  SurfaceMesh dm;
  t0 = std::chrono::steady_clock::now();
  try {
    dm = durix::make_delaunay_mesh(mesh, {}, &conv);
  } catch (const std::exception& e) {
    std::printf("| %s | %zu | conversion failed: %s |\n", name.c_str(), mesh.vertices.size(), e.what());
    std::fflush(stdout);
    return;
  }
  const double t_conv = seconds_since(t0);
  const durix::EpsilonOracle oracle(eps * bbox_diagonal(dm.vertices));
  durix::DurixResult r;
  t0 = std::chrono::steady_clock::now();
  try {
    r = durix::durix_medial_axis(dm, oracle);
  } catch (const std::exception& e) {
    std::printf("| %s | %zu | durix failed: %s |\n", name.c_str(), mesh.vertices.size(), e.what());
    std::fflush(stdout);
    return;
  }
  const double t_durix = seconds_since(t0);
  const auto& rep = r.report;
  const auto mt = services::complex_topology(r.medial);
  const auto st = services::surface_topology(r.surface);
  const bool chi_ok = 2 * mt.euler == st.complex.euler;
  std::printf("| %s | %zu | %zu (+%zu: %zu flips, %zu+%zu splits) | %lld | %.0f | %zu | %zu | %zu | %zu / %zu | %zu | "
              "%zu+%zu | %zu | %s | %zu/%zu/%zu | %.4f | %.2f | %.2f | %.2f | %.2f |\n",
              name.c_str(), mesh.vertices.size(), dm.vertices.size(), dm.vertices.size() - mesh.vertices.size(),
              conv.flips, conv.edge_splits, conv.face_splits, genus_in, st.genus(), rep.nodes, rep.medial_edges,
              rep.medial_faces, rep.sheets, rep.curve_sheets, rep.removed_vertices, rep.removals,
              rep.boundary_removals, rep.problematic_edges, chi_ok ? "yes" : "NO", rep.unclosed_paths,
              rep.loop_corner_errors, rep.problematic_left, rep.max_removed_excess / oracle.epsilon(), t_check,
              t_conv, t_durix, t_check + t_conv + t_durix);
  std::fprintf(stderr,
               "%s: dual %.2f s, propagation %.2f s (problematic %.2f s), output %.2f s; passes %d, candidates %zu, "
               "refused %zu/%zu/%zu, path failures %zu\n",
               name.c_str(), rep.seconds_dual, rep.seconds_propagation, rep.seconds_problematic, rep.seconds_output,
               rep.passes, rep.candidates, rep.rejected_not_separated, rep.rejected_manifold, rep.rejected_topology,
               rep.path_failures);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  double eps = 0.01;
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--eps" && i + 1 < argc) eps = std::stod(argv[++i]);
    else inputs.emplace_back(a);
  }
  if (inputs.empty()) inputs.emplace_back(MEDAX_SHARED_MESHES_DIR);
  std::vector<fs::path> files;
  for (const fs::path& in : inputs) {
    if (fs::is_directory(in)) {
      for (const auto& entry : fs::directory_iterator(in))
        if (entry.is_regular_file() && is_mesh(entry.path())) files.push_back(entry.path());
    } else {
      files.push_back(in);
    }
  }
  std::sort(files.begin(), files.end());
  std::printf("| mesh | V | V Delaunay (+added) | genus in | genus M_w | nodes | edges | faces | sheets / curves | "
              "removed V | carvings | problematic | χ(M)=χ(M_w)/2 | unclosed/corner err/problematic left | "
              "excess/ε | check s | convert s | durix s | total s |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|---|---:|---|---:|---|---|---:|---:|---:|---:|---:|\n");
  for (const fs::path& f : files) run_one(f, eps);
  return 0;
}
