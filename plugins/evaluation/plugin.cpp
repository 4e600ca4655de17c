// The evaluation package: reconstruction error, element counts and topology of a medial
// complex (docs/plugins/evaluation.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("evaluation", "0.1.0") {
  registrar.add<medax::evaluation::ReconstructionStage>();
  registrar.add<medax::evaluation::CountsStage>();
  registrar.add<medax::evaluation::TopologyStage>();
}
