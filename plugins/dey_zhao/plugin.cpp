// The dey_zhao package: one extraction stage (stages.hpp).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("dey_zhao", "1.0.0") { registrar.add<medax::dey_zhao::DeyZhaoStage>(); }
