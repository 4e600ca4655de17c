#pragma once
// Internal to et_skeleton: the surviving cells written into a Skeleton.
#include "skeleton_contraction.hpp"

namespace medax::et::skeleton {

/// Writes the cells the contraction left; with `coarsen`, whole input triangles as themselves.
void write_output(const BurnGraph& g, const Subdivision& sub, const CellComplex& k, const std::vector<double>& et_c,
                  const Contraction& alive, bool coarsen, Skeleton& out);

}  // namespace medax::et::skeleton
