// The coverage_axis package: Coverage Axis and Coverage Axis++ (docs/plugins/coverage_axis.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("coverage_axis", "1.0.0") { registrar.add<medax::coverage_axis::CoverageAxisStage>(); }
