#include "stages.hpp"

#include "counts.hpp"
#include "rebuilt_surface.hpp"

#include <medax/reconstructed_surface.hpp>
#include <medax/representation_size.hpp>

#include <medax/services/topology.hpp>

#include <fmt/format.h>

#include <ostream>
#include <stdexcept>

namespace medax::evaluation {

namespace {
constexpr const char* kDoc = "docs/plugins/evaluation.md";
}

// ---- reconstruction ----------------------------------------------------------------------

StageInfo ReconstructionStage::describe() {
  return {"reconstruction",
          "Two-sided distances (Hausdorff, MSD's mean errors) between the surface and the "
          "sphere/cone/slab envelope, or the rebuilt surface when a stage published one (MSD's Ŝ)",
          kDoc};
}

void ReconstructionStage::declare(ParamBinder& p) {
  p.add("resolution", options_.resolution,
        "Envelope boundary points lie on a grid of step = smallest side of the input's (or the envelope's, if "
        "smaller) bounding box / resolution (VMAS: 150)")
      .range(4, 4000);
  p.add("step", options_.step, "Absolute grid step in the shape's current frame; 0 uses `resolution`")
      .at_least(0)
      .in_unit("length");
  p.add("max_envelope_samples", options_.max_envelope_samples,
        "Budget of envelope points: if the surface's area would give more than this at the step from `resolution` "
        "(1.5 × area / step²), the step is enlarged to fit (slender shapes); 0: no budget, the VMAS rule alone (the "
        "sampling before issue 16); an explicit `step` is kept")
      .at_least(0);
  p.add("vertices", options_.use_vertices,
        "Measure surface→envelope from the mesh vertices that faces use (as the VMAS code)");
  p.add("surface_samples", options_.uniform_samples,
        "Area-uniform surface samples added to the vertices (seeded per stage)")
      .at_least(0);
  p.add("export_envelope", export_envelope_,
        "Write the envelope boundary points (x y z, normal, area, distance to the surface; in the input's frame, "
        "to overlay the input mesh) to `<id>_envelope.ply` in the run folder");
}

void ReconstructionStage::check_params() const {
  if (!options_.use_vertices && options_.uniform_samples == 0)
    throw std::invalid_argument("`vertices: false` needs `surface_samples` > 0");
}

void ReconstructionStage::check_scene(const Scene& scene) const {
  if (scene.medial->num_vertices() == 0)
    throw std::invalid_argument("the medial complex is empty; nothing to reconstruct");
  if (scene.shape.mesh.empty() && scene.shape.samples.empty())
    throw std::invalid_argument("the shape has neither a mesh nor samples to compare with");
}

Metrics ReconstructionStage::evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) {
  if (const ReconstructedSurface* rebuilt = ctx.data().find(kReconstructedSurface))
    return measure_rebuilt(shape, *rebuilt, ctx);
  return measure_envelope(shape, medial, ctx);
}

Metrics ReconstructionStage::measure_rebuilt(const Shape& shape, const ReconstructedSurface& rebuilt, Context& ctx) {
  ctx.progress(0.0, "rebuilt surface");
  const RebuiltSurfaceResult r =
      measure_rebuilt_surface(shape, rebuilt.surface, options_, ctx.rng(), [&ctx] { ctx.check_cancelled(); });
  ctx.info(fmt::format("measured the rebuilt surface published by '{}' ({}; {} vertices, {} faces), not the "
                       "envelope: {} shape samples, {} rebuilt samples; Hausdorff {:.4g}% of the bbox diagonal",
                       ctx.data().publisher(kReconstructedSurface.name), rebuilt.method,
                       rebuilt.surface.vertices.size(), rebuilt.surface.faces.size(), r.surface_samples,
                       r.rebuilt_samples, 100.0 * r.hausdorff() / r.diagonal));
  if (export_envelope_) ctx.warn("`export_envelope` is ignored: the rebuilt surface was measured, not the envelope");
  return r.metrics();
}

Metrics ReconstructionStage::measure_envelope(const Shape& shape, const MedialComplex& medial, Context& ctx) {
  const ReconstructionResult r =
      measure_reconstruction(
          shape, medial, options_, ctx.rng(),
          [&ctx](double f, std::string_view what) {
            ctx.check_cancelled();
            ctx.progress(f, what);
          },
          [&ctx] { ctx.check_cancelled(); });
  // The budget is the default sampling (docs/plugins/evaluation.md), so enlarging the step is
  // news, not a problem.
  if (r.step > r.requested_step)
    ctx.info(fmt::format("the step {:g} from `resolution` would give more than {} envelope points on this surface; "
                         "using step {:g} (`max_envelope_samples: 0` keeps the VMAS rule's step)",
                         r.requested_step, options_.max_envelope_samples, r.step));
  if (r.envelope.size() == 0)
    ctx.warn(fmt::format("no envelope boundary point was found at step {:g} (the envelope is thinner than the grid); "
                         "envelope→surface distances are 0. Lower `step` or raise `resolution`.",
                         r.step));
  ctx.info(fmt::format("envelope: {} primitives, {} boundary points at step {:g}; {} surface samples; "
                       "Hausdorff {:.4g}% of the bbox diagonal",
                       r.primitives, r.envelope.size(), r.step, r.surface_samples, 100.0 * r.hausdorff() / r.diagonal));
  if (export_envelope_) {
    const std::string name = (id().empty() ? std::string("reconstruction") : id()) + "_envelope.ply";
    // In the input's frame, like the medial outputs, so that it overlays the input mesh.
    ctx.write_output(name, [&r, &shape](std::ostream& out) { write_envelope_ply(out, r, shape.to_input); });
  }
  return r.metrics();
}

// ---- counts ------------------------------------------------------------------------------

StageInfo CountsStage::describe() {
  return {"counts",
          "Element counts #v, #e (edges in no triangle), #f, and MSD's N_d = #v+#e+#f and N_c = 4·#v (or the "
          "representation's own N_d, N_c when a stage published them, e.g. msd)",
          kDoc};
}

Metrics CountsStage::evaluate(const Shape&, const MedialComplex& medial, Context& ctx) {
  const ElementCounts counts = count_elements(medial);
  Metrics m = counts.metrics();
  if (const RepresentationSize* size = ctx.data().find(kRepresentationSize)) {
    m["N_d"] = static_cast<double>(size->discrete);
    m["N_c"] = static_cast<double>(size->continuous);
    ctx.info(fmt::format("N_d {} and N_c {} are the representation's size published by '{}' ({}), not the "
                         "complex's count (#v + #e + #f = {}, 4·#v = {})",
                         size->discrete, size->continuous, ctx.data().publisher(kRepresentationSize.name),
                         size->rule, counts.discrete(), counts.continuous()));
  }
  return m;
}

// ---- topology ----------------------------------------------------------------------------

StageInfo TopologyStage::describe() {
  return {"topology",
          "Components, Euler characteristic and Betti numbers b0, b1, b2 (over Z/2) of the complex, and the "
          "input surface's components, Euler characteristic and genus",
          kDoc};
}

void TopologyStage::declare(ParamBinder& p) {
  p.add("input", input_, "Also report the input surface's topology (the `input_*` metrics)");
}

Metrics TopologyStage::evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology t = services::complex_topology(medial);
  Metrics m{{"components", static_cast<double>(t.b0)},
            {"euler", static_cast<double>(t.euler)},
            {"b0", static_cast<double>(t.b0)},
            {"b1", static_cast<double>(t.b1)},
            {"b2", static_cast<double>(t.b2)}};
  if (input_ && !shape.mesh.empty()) {
    const services::SurfaceTopology s = services::surface_topology(shape.mesh);
    m["input_components"] = static_cast<double>(s.complex.b0);
    m["input_euler"] = static_cast<double>(s.complex.euler);
    m["input_b1"] = static_cast<double>(s.complex.b1);
    m["input_closed"] = s.closed() ? 1.0 : 0.0;
    m["input_genus"] = s.genus();
    if (!s.closed())
      ctx.warn(fmt::format("the input surface is not closed ({} boundary, {} non-manifold edges); input_genus is "
                           "reported as -1",
                           s.boundary_edges, s.nonmanifold_edges));
  }
  return m;
}

}  // namespace medax::evaluation
