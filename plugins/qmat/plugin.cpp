// The qmat package: Q-MAT simplification of a medial complex (docs/plugins/qmat.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("qmat", "1.0.0") { registrar.add<medax::qmat::QmatStage>(); }
