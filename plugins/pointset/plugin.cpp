// Registration of the pointset package.
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("pointset", "0.1.0") {
  registrar.add<medax::pointset::OutliersStage>();
  registrar.add<medax::pointset::NormalsStage>();
  registrar.add<medax::pointset::SmoothPointsStage>();
  registrar.add<medax::pointset::SimplifyPointsStage>();
  registrar.add<medax::pointset::ReconstructMeshStage>();
}
