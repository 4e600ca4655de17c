// The voronoi package: the interior Voronoi diagram, the raw discrete medial axis
// (docs/plugins/voronoi.md).
#include "stages.hpp"

#include <medax/plugin.hpp>

MEDAX_PLUGIN("voronoi", "1.0.0") { registrar.add<medax::voronoi::VoronoiStage>(); }
