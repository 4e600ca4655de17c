// The vmas package: VMAS extraction and its dual connectivity (docs/plugins/vmas.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("vmas", "0.1.0") {
  registrar.add<medax::vmas::VmasStage>();
  registrar.add<medax::vmas::VmasDualStage>();
}
