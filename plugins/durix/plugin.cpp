// Registration of the durix package (Durix, Leonard, Chambon, Morin 2023).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("durix", "1.0.0") {
  registrar.add<medax::durix::DelaunaySurfaceStage>();
  registrar.add<medax::durix::DurixStage>();
  registrar.add<medax::durix::EpsilonOracleStage>();
}
