// durix_medial_axis(): the Dual, the seeds, the engine, the outputs.
#include "durix.hpp"

#include "engine.hpp"
#include "output.hpp"

#include <medax/services/inside.hpp>

#include <algorithm>
#include <chrono>

namespace medax::durix {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
  // Seeds (notes §3.2, made deterministic): per component, the largest ball with a medial face
  // whose centre is inside the input surface (flat cells at the surface have huge balls whose
  // centres lie outside: Appendix A).
  {
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
    services::InsideTest inside(mesh);
    std::vector<int> tries(engine.preferred_seed.size(), 0);
    for (CellId c : order) {
      const auto comp = static_cast<std::size_t>(dual.component(c));
      if (engine.preferred_seed[comp] != kNoId || tries[comp] > 256) continue;
      ++tries[comp];
      if (inside.inside(dual.centre(c))) engine.preferred_seed[comp] = c;
    }
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
