#include "stages.hpp"

#include "counts.hpp"
#include "reconstruction.hpp"

#include <medax/services/topology.hpp>

#include <fmt/format.h>

#include <ostream>
#include <stdexcept>

namespace medax::evaluation {

namespace {
constexpr const char* kDoc = "docs/plugins/evaluation.md";
}

// ---- reconstruction ----------------------------------------------------------------------

StageInfo Reconstruction::describe() {
  return {"reconstruction",
          "Two-sided distances (Hausdorff, MSD's mean errors) between the surface and the "
          "sphere/cone/slab envelope",
          kDoc,
          {ParamSpec::integer("resolution", 150,
                              "Envelope boundary points lie on a grid of step = smallest side of the input's "
                              "(or the envelope's, if smaller) bounding box / resolution (VMAS: 150)")
               .range(4, 4000),
           ParamSpec::real("step", 0.0, "Absolute grid step in the shape's current frame; 0 uses `resolution`")
               .at_least(0)
               .in_unit("length"),
           ParamSpec::integer("max_envelope_samples", 5000000,
                              "Guard for thin shapes: if the surface's area would give more envelope points "
                              "than this, the step is enlarged to fit, with a warning (0: no guard)")
               .at_least(0),
           ParamSpec::boolean("vertices", true, "Measure surface→envelope from the mesh vertices (as the VMAS code)"),
           ParamSpec::integer("surface_samples", 0,
                              "Area-uniform surface samples added to the vertices (seeded per stage)")
               .at_least(0),
           ParamSpec::boolean("export_envelope", false,
                              "Write the envelope boundary points (with normals, areas and distances to the "
                              "surface, in the input's frame) to <id>_envelope.ply in the run folder")}};
}

void Reconstruction::prepare(const Scene& scene) const {
  EvaluationStage::prepare(scene);
  if (scene.medial->num_vertices() == 0)
    throw std::invalid_argument("reconstruction: the medial complex is empty; nothing to reconstruct");
  if (scene.shape.mesh.empty() && scene.shape.samples.empty())
    throw std::invalid_argument("reconstruction: the shape has neither a mesh nor samples to compare with");
  if (!params().boolean("vertices") && params().integer("surface_samples") == 0)
    throw std::invalid_argument("reconstruction: `vertices: false` needs `surface_samples` > 0");
}

Metrics Reconstruction::evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) {
  ReconstructionOptions options;
  options.resolution = static_cast<int>(params().integer("resolution"));
  options.step = params().real("step");
  options.use_vertices = params().boolean("vertices");
  options.uniform_samples = static_cast<std::size_t>(params().integer("surface_samples"));
  options.max_envelope_samples = static_cast<std::size_t>(params().integer("max_envelope_samples"));
  const ReconstructionResult r = measure_reconstruction(
      shape, medial, options, ctx.rng(), [&ctx](double f, std::string_view what) {
        ctx.check_cancelled();
        ctx.progress(f, what);
      });
  if (r.step > r.requested_step)
    ctx.warn(fmt::format("reconstruction: the step {:g} would give more than {} envelope points on this surface; "
                         "using step {:g} instead (raise `max_envelope_samples` or set `step` to insist)",
                         r.requested_step, options.max_envelope_samples, r.step));
  if (r.envelope.size() == 0)
    ctx.warn("reconstruction: no envelope boundary point was found at step " + fmt::format("{:g}", r.step) +
             " (the envelope is thinner than the grid); envelope→surface distances are 0. Lower `step` or raise "
             "`resolution`.");
  ctx.info(fmt::format("envelope: {} primitives, {} boundary points at step {:g}; {} surface samples; "
                       "Hausdorff {:.4g}% of the bbox diagonal",
                       r.primitives, r.envelope.size(), r.step, r.surface_samples, 100.0 * r.hausdorff() / r.diagonal));
  if (params().boolean("export_envelope")) {
    const std::string name = (id().empty() ? std::string("reconstruction") : id()) + "_envelope.ply";
    // In the input's frame, like the medial outputs, so that it overlays the input mesh.
    const Similarity& frame = shape.to_input;
    ctx.write_output(name, [&r, &frame](std::ostream& out) {
      out << "ply\nformat ascii 1.0\ncomment medax reconstruction: points on the envelope boundary, input frame\n"
          << "element vertex " << r.envelope.size() << "\n"
          << "property double x\nproperty double y\nproperty double z\n"
          << "property double nx\nproperty double ny\nproperty double nz\n"
          << "property double area\nproperty double distance\nend_header\n";
      for (std::size_t i = 0; i < r.envelope.size(); ++i) {
        const Vec3 p = frame.apply(r.envelope.points[i]);
        const Vec3& n = r.envelope.normals[i];
        out << fmt::format("{:.17g} {:.17g} {:.17g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g}\n", p.x(), p.y(), p.z(), n.x(),
                           n.y(), n.z(), r.envelope.areas[i] * frame.scale * frame.scale,
                           frame.apply_length(r.envelope_distances[i]));
      }
    });
  }
  return r.metrics();
}

// ---- counts ------------------------------------------------------------------------------

StageInfo Counts::describe() {
  return {"counts",
          "Element counts #v, #e (edges in no triangle), #f, and MSD's N_d = #v+#e+#f and N_c = 4·#v",
          kDoc,
          {}};
}

Metrics Counts::evaluate(const Shape&, const MedialComplex& medial, Context&) {
  return count_elements(medial).metrics();
}

// ---- topology ----------------------------------------------------------------------------

StageInfo Topology::describe() {
  return {"topology",
          "Components, Euler characteristic and Betti numbers b0, b1, b2 (over Z/2) of the complex, and the "
          "input surface's components, Euler characteristic and genus",
          kDoc,
          {ParamSpec::boolean("input", true, "Also report the input surface's topology (input_* metrics)")}};
}

Metrics Topology::evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) {
  const services::ComplexTopology t = services::complex_topology(medial);
  Metrics m{{"components", static_cast<double>(t.b0)},
            {"euler", static_cast<double>(t.euler)},
            {"b0", static_cast<double>(t.b0)},
            {"b1", static_cast<double>(t.b1)},
            {"b2", static_cast<double>(t.b2)}};
  if (params().boolean("input") && !shape.mesh.empty()) {
    const services::SurfaceTopology s = services::surface_topology(shape.mesh);
    m["input_components"] = static_cast<double>(s.complex.b0);
    m["input_euler"] = static_cast<double>(s.complex.euler);
    m["input_b1"] = static_cast<double>(s.complex.b1);
    m["input_closed"] = s.closed() ? 1.0 : 0.0;
    m["input_genus"] = s.genus();
    if (!s.closed())
      ctx.warn(fmt::format("topology: the input surface is not closed ({} boundary, {} non-manifold edges); "
                           "input_genus is reported as -1",
                           s.boundary_edges, s.nonmanifold_edges));
  }
  return m;
}

}  // namespace medax::evaluation
