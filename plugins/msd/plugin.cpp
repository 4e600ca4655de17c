// The msd package: the Medial Skeletal Diagram (Guo, Wang, Matusik 2024; docs/plugins/msd.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("msd", "1.0.0") {
  registrar.add<medax::msd::MsdStage>();
  registrar.add<medax::msd::MsdMedialStage>();
}
