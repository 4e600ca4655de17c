// durix_medial_axis(): the Dual, the seeds, the engine, the outputs.
#include "durix.hpp"

#include "engine.hpp"
#include "output.hpp"

#include <medax/services/ray_parity.hpp>

#include <algorithm>
#include <chrono>

namespace medax::durix {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Solid cells with a medial face (a volumetric edge), largest ball first.
std::vector<CellId> seed_candidates_by_radius(const Dual& dual) {
  std::vector<CellId> order;
  for (CellId c = 0; c < dual.num_cells(); ++c) {
    if (!dual.solid(c)) continue;
    for (int p = 0; p < 6; ++p)
      if (dual.volumetric(dual.cell_edge(c, p))) {
        order.push_back(c);
        break;
      }
  }
  std::sort(order.begin(), order.end(), [&](CellId a, CellId b) {
    return dual.radius(a) != dual.radius(b) ? dual.radius(a) > dual.radius(b) : a < b;
  });
  return order;
}
}  // namespace

DurixResult durix_medial_axis(const SurfaceMesh& mesh, const RegionOracle& oracle, const DurixOptions& options,
                              const ProgressFn& progress, const CancelFn& check_cancelled) {
  DurixResult result;
  DurixReport& r = result.report;
  r.input_vertices = mesh.vertices.size();
  r.input_faces = mesh.faces.size();
  r.epsilon = oracle.epsilon();
  if (progress) progress(0.0, "Delaunay tetrahedralization");
  auto t0 = std::chrono::steady_clock::now();
  Dual dual(mesh.vertices, mesh.faces);
  r.dt_cells = dual.num_cells();
  for (CellId c = 0; c < dual.num_cells(); ++c) r.interior_cells += dual.solid(c);
  r.components = static_cast<std::size_t>(dual.num_components());
  r.seconds_dual = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  Engine engine(dual, oracle, options, r, check_cancelled);
  // Which balls are centred inside the input (exact ray parity, in parallel): for the seeds
  // and for the Appendix A removal of outside-centre cells.
  {
    std::vector<Vec3> centres;
    std::vector<CellId> solid_cells;
    for (CellId c = 0; c < dual.num_cells(); ++c)
      if (dual.solid(c)) {
        solid_cells.push_back(c);
        centres.push_back(dual.centre(c));
      }
    const std::vector<char> inside = services::RayParityInside(mesh).inside(centres);
    engine.centre_inside.assign(dual.num_cells(), 1);
    for (std::size_t i = 0; i < solid_cells.size(); ++i) engine.centre_inside[solid_cells[i]] = inside[i];
  }
  // Seeds (notes §3.2, made deterministic): per component, the largest ball with a medial face
  // whose centre is inside the input surface (flat cells at the surface have huge balls whose
  // centres lie outside: Appendix A).
  for (CellId c : seed_candidates_by_radius(dual)) {
    CellId& seed = engine.preferred_seed[static_cast<std::size_t>(dual.component(c))];
    if (seed == kNoId && engine.centre_inside[c]) seed = c;
  }
  engine.run(progress);
  r.seconds_propagation = seconds_since(t0);

  if (progress) progress(0.9, "output");
  t0 = std::chrono::steady_clock::now();
  build_output(engine, mesh, result);
  r.seconds_output = seconds_since(t0);
  return result;
}

}  // namespace medax::durix
