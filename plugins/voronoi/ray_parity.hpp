#pragma once
// The exact batch inside test now lives in the geometry services (medax/services/ray_parity.hpp),
// shared with the dey_zhao extraction; this alias keeps the voronoi package's name for it.
#include <medax/services/ray_parity.hpp>

namespace medax::voronoi {

using services::RayParityInside;

}  // namespace medax::voronoi
