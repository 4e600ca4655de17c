// Runs delaunay_surface (DZM07, remesh fallback) + durix on meshes and prints one Markdown row
// per mesh, with the conversion method used and the invariants checked on the result (not a
// ctest: real meshes take seconds each).
//
//   durix_real_meshes [--eps 0.01] [--method dzm07|remesh] [--no-fallback]
//                     [--facet-size 0.6] [--facet-distance 0.001] [MESH_OR_FOLDER ...]
//                     (default: the corpus folder data/meshes; scripts/fetch-meshes.sh)
#include "durix.hpp"
#include "remesh_fallback.hpp"

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

void run_one(const fs::path& path, double eps, const durix::DelaunaySurfaceOptions& options) {
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
  durix::DelaunaySurfaceResult conversion;
  t0 = std::chrono::steady_clock::now();
  try {
    conversion = durix::make_delaunay_surface(mesh, options);
  } catch (const std::exception& e) {
    std::printf("| %s | %zu | conversion failed: %s |\n", name.c_str(), mesh.vertices.size(), e.what());
    std::fflush(stdout);
    return;
  }
  const double t_conv = seconds_since(t0);
  const SurfaceMesh& dm = conversion.mesh;
  const durix::DelaunayMeshReport& conv = conversion.dzm07;
  if (!conversion.dzm07_failure.empty())
    std::fprintf(stderr, "%s: DZM07 failed (%s); remeshed\n", name.c_str(), conversion.dzm07_failure.c_str());
  const std::string method =
      conversion.method == durix::DelaunayMethod::Dzm07
          ? "dzm07 (+" + std::to_string(dm.vertices.size() - mesh.vertices.size()) + ": " +
                std::to_string(conv.flips) + " flips, " + std::to_string(conv.edge_splits) + "+" +
                std::to_string(conv.face_splits) + " splits)"
          : std::string(conversion.dzm07_failure.empty() ? "remesh" : "remesh (fallback)") + ", Mesh_3 " +
                std::to_string(conversion.remesh.mesh3_vertices) + " V";
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
  std::printf("| %s | %zu | %zu | %s | %lld | %.0f | %zu | %zu | %zu | %zu / %zu | %zu | "
              "%zu+%zu | %zu | %s | %zu/%zu/%zu | %.4f | %.2f | %.2f | %.2f | %.2f |\n",
              name.c_str(), mesh.vertices.size(), dm.vertices.size(), method.c_str(), genus_in, st.genus(), rep.nodes, rep.medial_edges,
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
  durix::DelaunaySurfaceOptions options;
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--eps" && i + 1 < argc) eps = std::stod(argv[++i]);
    else if (a == "--method" && i + 1 < argc)
      options.method = std::string(argv[++i]) == "remesh" ? durix::DelaunayMethod::Remesh : durix::DelaunayMethod::Dzm07;
    else if (a == "--no-fallback") options.fallback = durix::DelaunayFallback::None;
    else if (a == "--facet-size" && i + 1 < argc) options.remesh.facet_size = std::stod(argv[++i]);
    else if (a == "--facet-distance" && i + 1 < argc) options.remesh.facet_distance = std::stod(argv[++i]);
    else inputs.emplace_back(a);
  }
  if (inputs.empty()) inputs.emplace_back(MEDAX_CORPUS_DIR);
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
  std::printf("| mesh | V | V Delaunay | method | genus in | genus M_w | nodes | edges | faces | sheets / curves | "
              "removed V | carvings | problematic | χ(M)=χ(M_w)/2 | unclosed/corner err/problematic left | "
              "excess/ε | check s | convert s | durix s | total s |\n");
  std::printf("|---|---:|---:|---|---:|---:|---:|---:|---:|---|---:|---|---:|---|---|---:|---:|---:|---:|---:|\n");
  for (const fs::path& f : files) run_one(f, eps, options);
  return 0;
}
