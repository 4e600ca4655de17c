// A complete medax plugin: one evaluation stage that compares the volume of the medial spheres
// with the volume enclosed by the surface mesh.
#include <medax/plugin.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Volume enclosed by a closed, outward-oriented triangle mesh (divergence theorem).
double enclosed_volume(const medax::SurfaceMesh& mesh) {
  double volume = 0;
  for (const medax::Tri& f : mesh.faces)
    volume += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]])) / 6.0;
  return volume;
}

class HelloVolume : public medax::EvaluationStage {
 public:
  static medax::StageInfo describe() {
    return {"hello_volume", "Sum and largest of the medial sphere volumes, against the enclosed mesh volume",
            "examples/hello_plugin/README.md"};
  }

  // Each parameter once: its name, the field that holds it (whose initial value is the
  // default), its doc, then its range and unit.
  void declare(medax::ParamBinder& p) override {
    p.add("min_radius", min_radius_, "ignore spheres smaller than this").at_least(0).in_unit("input length");
  }

  medax::Metrics evaluate(const medax::Shape& shape, const medax::MedialComplex& medial,
                          medax::Context& ctx) override {
    double sum = 0, largest = 0;
    std::size_t used = 0;
    for (double r : medial.radii) {
      if (r < min_radius_) continue;
      const double v = 4.0 / 3.0 * kPi * r * r * r;
      sum += v;
      largest = std::max(largest, v);
      ++used;
    }
    const double mesh_volume = enclosed_volume(shape.mesh);
    ctx.info("summed " + std::to_string(used) + " of " + std::to_string(medial.num_vertices()) + " spheres");
    return {{"sphere_volume_sum", sum},
            {"largest_sphere_volume", largest},
            {"mesh_volume", mesh_volume},
            {"largest_sphere_fraction", mesh_volume > 0 ? largest / mesh_volume : NAN}};
  }

 private:
  double min_radius_ = 0.0;
};

}  // namespace

MEDAX_PLUGIN("hello", "1.0.0") { registrar.add<HelloVolume>(); }
