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

/// Where the Delaunay points come from.
enum class Points { Auto, Vertices, Samples };

class DeyZhaoStage : public ExtractionStage {
 public:
  static StageInfo describe() {
    return {"dey_zhao",
            "Medial axis as the Voronoi facets whose dual Delaunay edges pass the Angle or Ratio condition "
            "(Dey & Zhao 2004)",
            "docs/plugins/dey_zhao.md"};
  }

  void declare(ParamBinder& p) override {
    using dey_zhao::InnerSelection;
    p.add("points", points_, {{"auto", Points::Auto}, {"vertices", Points::Vertices}, {"samples", Points::Samples}},
          "Delaunay of the oriented samples (from a `sample` stage) or of the mesh vertices; auto: the samples when "
          "there are some");
    p.add("angle_condition", options_.angle_condition, "select edges by the Angle condition [theta]");
    p.add("theta", options_.theta,
          "Angle condition: the edge makes more than theta with every umbrella triangle at one end (paper: pi/8)")
        .range(0, dey_zhao::kPi / 2)
        .in_unit("rad");
    p.add("ratio_condition", options_.ratio_condition, "select edges by the Ratio condition [rho]");
    p.add("rho", options_.rho,
          "Ratio condition: the edge is longer than rho times every umbrella circumradius at one end (paper: 8)")
        .at_least(0)
        .in_unit("ratio");
    p.add("inner", options_.inner,
          {{"auto", InnerSelection::Auto},
           {"delaunay_surface", InnerSelection::DelaunaySurface},
           {"mesh", InnerSelection::Mesh},
           {"normals", InnerSelection::Normals},
           {"none", InnerSelection::None}},
          "which facets are inner: mesh triangles that are Delaunay facets (flood fill, as the paper), a closed mesh "
          "(edge midpoint inside, edge not crossing it), outward normals, or none (inner and outer axis); auto: the "
          "first that applies");
    p.add("unbounded", options_.unbounded, {{"drop", dey_zhao::Unbounded::Drop}, {"clip", dey_zhao::Unbounded::Clip}},
          "facets dual to convex-hull edges are unbounded: drop them, or clip their rays");
    p.add("clip_factor", options_.clip_factor, "unbounded: clip: length of the clipped rays")
        .at_least(0)
        .in_unit("bbox diagonal");
    p.add("merge_tolerance", options_.merge_tolerance, "facet vertices closer than this are one vertex (cospherical points)")
        .at_least(0)
        .in_unit("bbox diagonal");
  }

  void check_params() const override {
    if (!options_.angle_condition && !options_.ratio_condition)
      throw std::invalid_argument("`angle_condition` and `ratio_condition` are both false, so no facet can be "
                                  "selected; enable at least one");
    if (options_.unbounded == dey_zhao::Unbounded::Clip && !(options_.clip_factor > 0))
      throw std::invalid_argument("`unbounded: clip` needs `clip_factor` > 0");
  }

  void check_scene(const Scene& scene) const override { check(scene.shape); }

 private:
  bool use_samples(const Shape& shape) const {
    return points_ == Points::Samples || (points_ == Points::Auto && !shape.samples.empty());
  }

  /// Refuses, with what to do, data this stage cannot work on.
  void check(const Shape& shape) const {
    using dey_zhao::InnerSelection;
    if (use_samples(shape)) {
      if (shape.samples.empty())
        throw std::invalid_argument("`points: samples` but the shape has no samples; add a `sample` stage before it, "
                                    "or use `points: vertices`");
      if (shape.samples.size() < 4) throw std::invalid_argument("fewer than 4 samples");
      if (options_.inner == InnerSelection::DelaunaySurface)
        throw std::invalid_argument("`inner: delaunay_surface` needs the mesh vertices as the points "
                                    "(`points: vertices`); with samples use `inner: mesh` or `normals`");
    } else if (shape.mesh.vertices.size() < 4) {
      throw std::invalid_argument("the shape has no surface mesh (at least 4 vertices) and no samples to take the "
                                  "Delaunay tetrahedralization of");
    }
    if ((options_.inner == InnerSelection::Mesh || options_.inner == InnerSelection::DelaunaySurface) &&
        shape.mesh.empty())
      throw std::invalid_argument(fmt::format("`inner: {}` needs a surface mesh; use `inner: normals` or `none`",
                                              dey_zhao::to_string(options_.inner)));
  }

 public:
  MedialComplex extract(const Shape& shape, Context& ctx) override {
    check_params();
    check(shape);
    const bool samples = use_samples(shape);
    dey_zhao::MedialOptions options = options_;
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
    MedialComplex medial = dey_zhao::medial_axis(input, options, &report);
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
      ctx.warn(fmt::format("{} points have an empty umbrella and select nothing", report.empty_umbrellas));
    if (medial.faces.empty()) ctx.warn("no facet was selected; the complex is empty");
    return medial;
  }

 private:
  Points points_ = Points::Auto;
  dey_zhao::MedialOptions options_;  // every field but generator_kind and parallel is a parameter
};

}  // namespace

MEDAX_PLUGIN("dey_zhao", "1.0.0") { registrar.add<DeyZhaoStage>(); }
