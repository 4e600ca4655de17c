// The `dey_zhao` extraction stage: MEDIAL (Dey & Zhao 2004), the Voronoi facets selected by the
// Angle and Ratio conditions. The algorithm lives in medial.cpp; this file declares the
// parameters, checks them against the data, and calls it.
#include "stages.hpp"

#include <medax/services/sampling.hpp>

#include <fmt/format.h>

#include <stdexcept>

namespace medax::dey_zhao {

StageInfo DeyZhaoStage::describe() {
  return {"dey_zhao",
          "Medial axis as the Voronoi facets whose dual Delaunay edges pass the Angle or Ratio condition "
          "(Dey & Zhao 2004)",
          "docs/plugins/dey_zhao.md"};
}

void DeyZhaoStage::declare(ParamBinder& p) {
  p.add("points", points_,
        {{"auto", PointSource::Auto}, {"vertices", PointSource::Vertices}, {"samples", PointSource::Samples}},
        "Delaunay of the oriented samples (from a `sample` stage) or of the mesh vertices; auto: the samples when "
        "there are some");
  p.add("angle_condition", options_.angle_condition, "select edges by the Angle condition [theta]");
  p.add("theta", options_.theta,
        "Angle condition: the edge makes more than theta with every umbrella triangle at one end (paper: "
        "theta_0 = pi/8)")
      .range(0, kPi / 2)
      .in_unit("rad");
  p.add("ratio_condition", options_.ratio_condition, "select edges by the Ratio condition [rho]");
  p.add("rho", options_.rho,
        "Ratio condition: the edge is longer than rho times every umbrella circumradius at one end (paper: "
        "rho_0 = 8)")
      .at_least(0)
      .in_unit("ratio");
  p.add("inner", options_.inner, inner_selection_names(),
        "which selected facets are kept: delaunay_surface (mesh triangles that are Delaunay facets: flood fill, the "
        "paper's rule), mesh (closed mesh: edge midpoint inside, edge not crossing it), normals (the edge leaves "
        "both ends inwards), none (inner and outer axis); auto: the first that applies");
  p.add("unbounded", options_.unbounded, {{"drop", Unbounded::Drop}, {"clip", Unbounded::Clip}},
        "facets dual to convex-hull edges are unbounded: drop them (counted in the log), or clip their rays");
  p.add("clip_factor", options_.clip_factor,
        "with `unbounded: clip`: length of the clipped rays, from their circumcentre")
      .at_least(0)
      .in_unit("bbox diagonal");
  p.add("merge_tolerance", options_.merge_tolerance,
        "facet vertices closer than this are one vertex (cospherical points)")
      .at_least(0)
      .in_unit("bbox diagonal");
}

void DeyZhaoStage::check_params() const {
  if (!options_.angle_condition && !options_.ratio_condition)
    throw std::invalid_argument("`angle_condition` and `ratio_condition` are both false, so no facet can be "
                                "selected; enable at least one");
  if (options_.unbounded == Unbounded::Clip && !(options_.clip_factor > 0))
    throw std::invalid_argument("`unbounded: clip` needs `clip_factor` > 0");
}

void DeyZhaoStage::check_scene(const Scene& scene) const { check(scene.shape); }

std::vector<ShapePart> DeyZhaoStage::needs() const {
  if (points_ == PointSource::Samples) return {ShapePart::Samples};
  return {};
}

bool DeyZhaoStage::use_samples(const Shape& shape) const {
  return points_ == PointSource::Samples || (points_ == PointSource::Auto && !shape.samples.empty());
}

void DeyZhaoStage::check(const Shape& shape) const {
  if (use_samples(shape)) {
    if (shape.samples.empty())
      throw std::invalid_argument("`points: samples` but the shape has no samples; add a `sample` stage before it, "
                                  "or use `points: vertices`");
    if (shape.samples.size() < 4) throw std::invalid_argument("fewer than 4 samples");
    if (options_.inner == InnerSelection::DelaunaySurface)
      throw std::invalid_argument("`inner: delaunay_surface` needs the mesh vertices as the points "
                                  "(`points: vertices`); with samples use `inner: mesh` or `normals`");
    if (options_.inner == InnerSelection::Normals && shape.samples.normals.size() != shape.samples.size())
      throw std::invalid_argument("`inner: normals` needs oriented samples and these have no normals: put a "
                                  "`normals` stage before it");
  } else if (shape.mesh.vertices.size() < 4) {
    throw std::invalid_argument("the shape has no surface mesh (at least 4 vertices) and no samples to take the "
                                "Delaunay tetrahedralization of");
  }
  if ((options_.inner == InnerSelection::Mesh || options_.inner == InnerSelection::DelaunaySurface) &&
      shape.mesh.empty())
    throw std::invalid_argument(
        fmt::format("`inner: {}` needs a surface mesh; use `inner: normals` or `none`, or put `reconstruct_mesh` "
                    "before it",
                    to_string(options_.inner)));
}

namespace {

/// The log lines of one run.
void log_report(const MedialReport& report, const MedialComplex& medial, bool samples, Unbounded unbounded,
                Context& ctx) {
  ctx.info(fmt::format("{} {} points, {} Delaunay cells, {} Delaunay edges; {} points on the hull, {} empty "
                       "umbrellas",
                       report.points, samples ? "sample" : "vertex", report.cells, report.delaunay_edges,
                       report.hull_points, report.empty_umbrellas));
  ctx.info(fmt::format("selected {} edges (angle {}, ratio {}); {} unbounded{}; inner selection `{}` ({}) "
                       "rejected {}",
                       report.selected, report.selected_angle, report.selected_ratio, report.unbounded,
                       unbounded == Unbounded::Drop ? " dropped" : " clipped", to_string(report.inner_used),
                       report.inner_note, report.outer));
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
}

}  // namespace

MedialComplex DeyZhaoStage::extract(const Shape& shape, Context& ctx) {
  check_params();
  check(shape);
  const bool samples = use_samples(shape);
  MedialOptions options = options_;
  options.generator_kind = samples ? "sample" : "mesh_vertex";

  MedialInput input;
  std::vector<Vec3> vertex_normals;
  if (samples) {
    input.points = &shape.samples.points;
    if (shape.samples.normals.size() == shape.samples.size()) input.normals = &shape.samples.normals;
  } else {
    input.points = &shape.mesh.vertices;
    input.points_are_mesh_vertices = true;
    if (options.inner == InnerSelection::Normals || options.inner == InnerSelection::Auto) {
      vertex_normals = services::vertex_samples(shape.mesh).normals;
      input.normals = &vertex_normals;
    }
  }
  if (!shape.mesh.empty()) input.mesh = &shape.mesh;

  MedialReport report;
  MedialComplex medial = medial_axis(input, options, &report);
  log_report(report, medial, samples, options.unbounded, ctx);
  if (options.inner == InnerSelection::Auto && report.inner_used == InnerSelection::None)
    ctx.warn("no mesh and no normals tell inside from outside, so the complex holds the outer medial axis too: put "
             "a `normals` stage before it");
  return medial;
}

}  // namespace medax::dey_zhao
