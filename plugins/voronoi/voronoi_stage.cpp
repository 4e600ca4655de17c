// The `voronoi` extraction stage: the interior Voronoi diagram of the surface vertices (or
// samples). The algorithm lives in interior_voronoi.cpp; this file declares the parameters,
// checks them against the data, and calls it.
#include "interior_voronoi.hpp"

#include <medax/plugin.hpp>

#include <fmt/format.h>

#include <stdexcept>

namespace {

using namespace medax;

class VoronoiStage : public ExtractionStage {
 public:
  static StageInfo describe() {
    return {"voronoi",
            "Interior Voronoi diagram of the surface points: circumcentres of the Delaunay cells inside the mesh",
            "docs/plugins/voronoi.md",
            {ParamSpec::choice("points", "vertices", {"vertices", "samples"},
                               "Delaunay of the mesh vertices, or of the oriented samples (from a `sample` stage)"),
             ParamSpec::choice("connectivity", "faces", {"faces", "edges", "none"},
                               "Voronoi edges and fan-triangulated Voronoi faces, edges only, or spheres only"),
             ParamSpec::choice("inside_test", "ray_grid", {"ray_grid", "side_of_mesh"},
                               "exact classification of circumcentres: +x ray parity over a grid (fast) or "
                               "CGAL Side_of_triangle_mesh (reference); both give the same answer")}};
  }

  void prepare(const Scene& scene) const override { check(scene.shape); }

  /// Refuses, with what to do, data this stage cannot work on.
  void check(const Shape& shape) const {
    if (params().text("points") == "samples") {
      if (shape.samples.empty())
        throw std::invalid_argument("voronoi: `points: samples` but the shape has no samples; add a `sample` "
                                    "stage before it, or use `points: vertices`");
      if (shape.mesh.empty())
        throw std::invalid_argument("voronoi: `points: samples` needs the surface mesh as well, to tell which "
                                    "circumcentres are inside; samples alone have no inside");
    } else if (shape.mesh.empty() || shape.mesh.vertices.size() < 4) {
      throw std::invalid_argument("voronoi: the shape has no surface mesh (at least 4 vertices) to take the "
                                  "Delaunay tetrahedralization of");
    }
  }

  MedialComplex extract(const Shape& shape, Context& ctx) override {
    check(shape);
    voronoi::InteriorVoronoiOptions options;
    const bool samples = params().text("points") == "samples";
    options.generator_kind = samples ? "sample" : "mesh_vertex";
    const std::string& connectivity = params().text("connectivity");
    options.connectivity = connectivity == "faces"   ? voronoi::Connectivity::Faces
                           : connectivity == "edges" ? voronoi::Connectivity::Edges
                                                     : voronoi::Connectivity::None;
    options.inside = params().text("inside_test") == "side_of_mesh" ? voronoi::InsideMethod::SideOfMesh
                                                                    : voronoi::InsideMethod::RayGrid;
    voronoi::InteriorVoronoiReport report;
    MedialComplex medial;
    try {
      medial = voronoi::interior_voronoi(samples ? shape.samples.points : shape.mesh.vertices, shape.mesh,
                                         options, &report);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("voronoi: ") + e.what());
    }
    ctx.info(fmt::format("{} points, {} Delaunay cells, {} interior ({:.1f}%); {} Voronoi edges, {} Voronoi faces "
                         "({} triangles)",
                         report.points, report.cells, report.interior,
                         report.cells ? 100.0 * report.interior / report.cells : 0.0, report.voronoi_edges,
                         report.voronoi_faces, medial.faces.size()));
    ctx.info(fmt::format("time: Delaunay {:.3f} s, inside test {:.3f} s, complex {:.3f} s", report.seconds_delaunay,
                         report.seconds_inside, report.seconds_complex));
    if (medial.num_vertices() == 0) ctx.warn("voronoi: no circumcentre is inside the mesh; the complex is empty");
    return medial;
  }
};

}  // namespace

MEDAX_PLUGIN("voronoi", "1.0.0") { registrar.add<VoronoiStage>(); }
