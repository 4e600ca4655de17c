// The erosion_thickness package: Erosion Thickness on 3D medial axes (Yan, Sykes, Chambers,
// Letscher, Ju, SIGGRAPH 2016) and the local measures it is compared with
// (docs/plugins/erosion_thickness.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("erosion_thickness", "0.1.0") {
  registrar.add<medax::et::ErosionThicknessStage>();
  registrar.add<medax::et::RadiusMeasureStage>();
  registrar.add<medax::et::ObjectAngleStage>();
  registrar.add<medax::et::CircumradiusStage>();
  registrar.add<medax::et::MedialCurvesStage>();
  registrar.add<medax::et::EtSkeletonStage>();
  registrar.add<medax::et::PureComplexStage>();
}
