#include "stages.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace medax::voronoi {

StageInfo VoronoiStage::describe() {
  return {"voronoi",
          "Interior Voronoi diagram of the surface points: circumcentres of the Delaunay cells inside the mesh",
          "docs/plugins/voronoi.md"};
}

void VoronoiStage::declare(ParamBinder& p) {
  p.add("points", points_, {{"vertices", Points::Vertices}, {"samples", Points::Samples}},
        "Delaunay of the mesh vertices, or of the oriented samples (a `sample` stage's, or a point cloud's)");
  p.add("connectivity", options_.connectivity,
        {{"faces", Connectivity::Faces}, {"edges", Connectivity::Edges}, {"none", Connectivity::None}},
        "Voronoi edges and fan-triangulated Voronoi faces, edges only, or spheres only");
  p.add("inside_test", options_.inside,
        {{"ray_grid", InsideMethod::RayGrid}, {"side_of_mesh", InsideMethod::SideOfMesh}, {"normals", InsideMethod::Normals}},
        "classification of circumcentres: against the mesh, exactly, by +x ray parity over a grid (fast) or CGAL "
        "Side_of_triangle_mesh (reference), which agree; or, for a point cloud, by the side of the cell's corners' "
        "oriented normals (with `points: samples`)");
}

void VoronoiStage::check_scene(const Scene& scene) const { check(scene.shape); }

std::vector<ShapePart> VoronoiStage::needs() const {
  if (points_ == Points::Samples) return {ShapePart::Samples};
  return {};
}

void VoronoiStage::check(const Shape& shape) const {
  const bool by_normals = options_.inside == InsideMethod::Normals;
  if (by_normals && points_ != Points::Samples)
    throw std::invalid_argument("`inside_test: normals` classifies by the samples' normals: use `points: samples`");
  if (points_ == Points::Samples) {
    if (shape.samples.empty())
      throw std::invalid_argument("`points: samples` but the shape has no samples; add a `sample` stage before it, "
                                  "or use `points: vertices`");
    if (by_normals && shape.samples.normals.size() != shape.samples.size())
      throw std::invalid_argument("`inside_test: normals` needs oriented samples and these have no normals: put a "
                                  "`normals` stage before it");
    if (!by_normals && shape.mesh.empty())
      throw std::invalid_argument("`points: samples` needs the surface mesh as well, to tell which circumcentres "
                                  "are inside; samples alone have no inside: for a point cloud use `inside_test: "
                                  "normals`, or put `reconstruct_mesh` before it");
  } else if (shape.mesh.empty() || shape.mesh.vertices.size() < 4) {
    throw std::invalid_argument(fmt::format(
        "the shape has no surface mesh (at least 4 vertices) to take the Delaunay tetrahedralization of{}",
        shape.samples.empty() ? ""
                              : "; for a point cloud use `points: samples` with `inside_test: normals`, or put "
                                "`reconstruct_mesh` before it"));
  }
}

MedialComplex VoronoiStage::extract(const Shape& shape, Context& ctx) {
  check(shape);
  const bool samples = points_ == Points::Samples;
  InteriorVoronoiOptions options = options_;
  options.generator_kind = samples ? "sample" : "mesh_vertex";
  InteriorVoronoiReport report;
  MedialComplex medial = options.inside == InsideMethod::Normals
                             ? interior_voronoi(shape.samples, options, &report)
                             : interior_voronoi(samples ? shape.samples.points : shape.mesh.vertices, shape.mesh,
                                                options, &report);
  ctx.info(fmt::format("{} points, {} Delaunay cells, {} interior ({:.1f}%); {} Voronoi edges, {} Voronoi faces "
                       "({} triangles)",
                       report.points, report.cells, report.interior,
                       report.cells ? 100.0 * report.interior / report.cells : 0.0, report.voronoi_edges,
                       report.voronoi_faces, medial.faces.size()));
  ctx.info(fmt::format("time: Delaunay {:.3f} s, inside test {:.3f} s, complex {:.3f} s", report.seconds_delaunay,
                       report.seconds_inside, report.seconds_complex));
  if (medial.num_vertices() == 0) ctx.warn("no circumcentre is inside the mesh; the complex is empty");
  return medial;
}

}  // namespace medax::voronoi
