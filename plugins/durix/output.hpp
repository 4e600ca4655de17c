#pragma once
// Internal: building the outputs of a run from the engine's final state.
#include "engine.hpp"

namespace medax::durix {

void build_output(const Engine& engine, const SurfaceMesh& mesh, DurixResult& result);

}  // namespace medax::durix
