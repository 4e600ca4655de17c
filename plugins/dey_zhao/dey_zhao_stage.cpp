// The `dey_zhao` extraction stage: MEDIAL (Dey & Zhao 2004), the Voronoi facets selected by the
// Angle and Ratio conditions. The algorithm lives in medial.cpp; this file declares the
// parameters, checks them against the data, and calls it.
#include "medial.hpp"

#include <medax/plugin.hpp>
#include <medax/services/sampling.hpp>

#include <fmt/format.h>

#include <stdexcept>

namespace {

using namespace medax;

class DeyZhaoStage : public ExtractionStage {
 public:
  static StageInfo describe() {
    return {"dey_zhao",
            "Medial axis as the Voronoi facets whose dual Delaunay edges pass the Angle or Ratio condition "
            "(Dey & Zhao 2004)",
            "docs/plugins/dey_zhao.md",
            {ParamSpec::choice("points", "auto", {"auto", "vertices", "samples"},
                               "Delaunay of the oriented samples (from a `sample` stage) or of the mesh vertices; "
                               "auto: the samples when there are some"),
             ParamSpec::boolean("angle_condition", true, "select edges by the Angle condition [theta]"),
             ParamSpec::real("theta", dey_zhao::kPi / 8,
                             "Angle condition: the edge makes more than theta with every umbrella triangle at one "
                             "end (paper: pi/8)")
                 .range(0, dey_zhao::kPi / 2)
                 .in_unit("rad"),
             ParamSpec::boolean("ratio_condition", true, "select edges by the Ratio condition [rho]"),
             ParamSpec::real("rho", 8.0,
                             "Ratio condition: the edge is longer than rho times every umbrella circumradius at one "
                             "end (paper: 8)")
                 .at_least(0)
                 .in_unit("ratio"),
             ParamSpec::choice("inner", "auto", {"auto", "delaunay_surface", "mesh", "normals", "none"},
                               "which facets are inner: mesh triangles that are Delaunay facets (flood fill, as the "
                               "paper), a closed mesh (edge midpoint inside, edge not crossing it), outward "
                               "normals, or none (inner and outer axis); auto: the first that applies"),
             ParamSpec::choice("unbounded", "drop", {"drop", "clip"},
                               "facets dual to convex-hull edges are unbounded: drop them, or clip their rays"),
             ParamSpec::real("clip_factor", 2.0, "unbounded: clip: length of the clipped rays")
                 .at_least(0)
                 .in_unit("bbox diagonal"),
             ParamSpec::real("merge_tolerance", 1e-12,
                             "facet vertices closer than this are one vertex (cospherical points)")
                 .at_least(0)
                 .in_unit("bbox diagonal")}};
  }

  void check_params() const override {
    if (!params().boolean("angle_condition") && !params().boolean("ratio_condition"))
      throw std::invalid_argument("dey_zhao: `angle_condition` and `ratio_condition` are both false, so no facet "
                                  "can be selected; enable at least one");
    if (params().text("unbounded") == "clip" && !(params().real("clip_factor") > 0))
      throw std::invalid_argument("dey_zhao: `unbounded: clip` needs `clip_factor` > 0");
  }

  void prepare(const Scene& scene) const override { check(scene.shape); }

  bool use_samples(const Shape& shape) const {
    const std::string& points = params().text("points");
    return points == "samples" || (points == "auto" && !shape.samples.empty());
  }

  /// Refuses, with what to do, data this stage cannot work on.
  void check(const Shape& shape) const {
    const std::string& inner = params().text("inner");
    if (use_samples(shape)) {
      if (shape.samples.empty())
        throw std::invalid_argument("dey_zhao: `points: samples` but the shape has no samples; add a `sample` "
                                    "stage before it, or use `points: vertices`");
      if (shape.samples.size() < 4)
        throw std::invalid_argument("dey_zhao: fewer than 4 samples");
      if (inner == "delaunay_surface")
        throw std::invalid_argument("dey_zhao: `inner: delaunay_surface` needs the mesh vertices as the points "
                                    "(`points: vertices`); with samples use `inner: mesh` or `normals`");
    } else if (shape.mesh.vertices.size() < 4) {
      throw std::invalid_argument("dey_zhao: the shape has no surface mesh (at least 4 vertices) and no samples to "
                                  "take the Delaunay tetrahedralization of");
    }
    if ((inner == "mesh" || inner == "delaunay_surface") && shape.mesh.empty())
      throw std::invalid_argument("dey_zhao: `inner: " + inner + "` needs a surface mesh; use `inner: normals` "
                                  "or `none`");
  }

  MedialComplex extract(const Shape& shape, Context& ctx) override {
    check_params();
    check(shape);
    const bool samples = use_samples(shape);
    dey_zhao::MedialOptions options;
    options.angle_condition = params().boolean("angle_condition");
    options.theta = params().real("theta");
    options.ratio_condition = params().boolean("ratio_condition");
    options.rho = params().real("rho");
    const std::string& inner = params().text("inner");
    options.inner = inner == "delaunay_surface" ? dey_zhao::InnerSelection::DelaunaySurface
                    : inner == "mesh"           ? dey_zhao::InnerSelection::Mesh
                    : inner == "normals"        ? dey_zhao::InnerSelection::Normals
                    : inner == "none"           ? dey_zhao::InnerSelection::None
                                                : dey_zhao::InnerSelection::Auto;
    options.unbounded = params().text("unbounded") == "clip" ? dey_zhao::Unbounded::Clip : dey_zhao::Unbounded::Drop;
    options.clip_factor = params().real("clip_factor");
    options.merge_tolerance = params().real("merge_tolerance");
    options.generator_kind = samples ? "sample" : "mesh_vertex";

    dey_zhao::MedialInput input;
    std::vector<Vec3> vertex_normals;
    if (samples) {
      input.points = &shape.samples.points;
      if (shape.samples.normals.size() == shape.samples.size()) input.normals = &shape.samples.normals;
    } else {
      input.points = &shape.mesh.vertices;
      input.points_are_mesh_vertices = true;
      if (options.inner == dey_zhao::InnerSelection::Normals || options.inner == dey_zhao::InnerSelection::Auto) {
        vertex_normals = services::vertex_samples(shape.mesh).normals;
        input.normals = &vertex_normals;
      }
    }
    if (!shape.mesh.empty()) input.mesh = &shape.mesh;

    dey_zhao::MedialReport report;
    MedialComplex medial;
    try {
      medial = dey_zhao::medial_axis(input, options, &report);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("dey_zhao: ") + e.what());
    }
    ctx.info(fmt::format("{} {} points, {} Delaunay cells, {} Delaunay edges; {} points on the hull, {} empty "
                         "umbrellas",
                         report.points, samples ? "sample" : "vertex", report.cells, report.delaunay_edges,
                         report.hull_points, report.empty_umbrellas));
    ctx.info(fmt::format("selected {} edges (angle {}, ratio {}); {} unbounded{}; inner selection `{}` ({}) "
                         "rejected {}",
                         report.selected, report.selected_angle, report.selected_ratio, report.unbounded,
                         options.unbounded == dey_zhao::Unbounded::Drop ? " dropped" : " clipped",
                         dey_zhao::to_string(report.inner_used), report.inner_note, report.outer));
    ctx.info(fmt::format("{} Voronoi facets ({} degenerate, {} merged vertices): {} vertices, {} edges, {} "
                         "triangles",
                         report.facets, report.degenerate_facets, report.merged_vertices, medial.num_vertices(),
                         medial.edges.size(), medial.faces.size()));
    ctx.info(fmt::format("time: Delaunay {:.3f} s; filtering {:.3f} s (umbrellas {:.3f}, conditions {:.3f}, inner "
                         "{:.3f}, complex {:.3f})",
                         report.seconds_delaunay, report.seconds_filtering(), report.seconds_umbrellas,
                         report.seconds_filter, report.seconds_inner, report.seconds_complex));
    if (report.empty_umbrellas)
      ctx.warn(fmt::format("dey_zhao: {} points have an empty umbrella and select nothing", report.empty_umbrellas));
    if (medial.faces.empty()) ctx.warn("dey_zhao: no facet was selected; the complex is empty");
    return medial;
  }
};

}  // namespace

MEDAX_PLUGIN("dey_zhao", "1.0.0") { registrar.add<DeyZhaoStage>(); }
