#pragma once
// Step 4a of the refinement: the band between a patch border and the border of the remaining
// template, triangulated in the direction domain (notes §2.8). A dynamic programme over the two
// loops (shortest total length of the new edges on the template surface ∂P^ρ0) admits only
// triangles that face away from their corners' bases in space and on ∂P^ρ0 (exact predicates),
// so the band never folds over along the direction field.
#include "refine_geometry.hpp"

#include <optional>
#include <vector>

namespace medax::msd::refine {

/// `inner`: a patch border, the patch on its left; `outer`: a border of the remaining template,
/// the template on its left; `points[id]` frames every id. nullopt when no consistent band was
/// found from the tried starting edges.
std::optional<std::vector<Tri>> stitch_band(const std::vector<Index>& inner, const std::vector<Index>& outer,
                                            const std::vector<FramedPoint>& points);

/// Closes a patch border with no template left to join (or none a band can reach) by a cap:
/// ear clipping of the loop on ∂P^ρ0, shortest new edge first, each ear consistent and holding
/// no other loop vertex in its cone from the element. nullopt when it gets stuck.
std::optional<std::vector<Tri>> cap_loop(const std::vector<Index>& loop, const std::vector<FramedPoint>& points);

}  // namespace medax::msd::refine
