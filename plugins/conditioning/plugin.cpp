// Registration of the conditioning package.
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("conditioning", "0.1.0") {
  registrar.add<medax::conditioning::NormalizeStage>();
  registrar.add<medax::conditioning::RepairStage>();
  registrar.add<medax::conditioning::SampleStage>();
}
