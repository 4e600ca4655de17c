#pragma once
// Combinatorics of triangle lists for the refinement: border loops, edge-connected components
// and the closed-2-manifold test. Vertex ids are whatever the caller uses (not compacted).
#include <medax/geometry.hpp>

#include <vector>

namespace medax::msd::refine {

/// The border of a triangle set: each loop follows the border halfedges (the faces on its left).
struct Borders {
  std::vector<std::vector<Index>> loops;
  /// Vertices where the border touches itself (two outgoing border halfedges): the faces do not
  /// form a surface with disk-like borders there.
  std::vector<Index> pinches;
};
Borders border_loops(const std::vector<Tri>& faces);

/// Edge-connected components: a component id per face, ids in order of first face.
std::vector<int> face_components(const std::vector<Tri>& faces, int* count);

/// Closed and 2-manifold: every directed edge once and its reverse present, every vertex one
/// fan, no degenerate face.
bool closed_manifold(const std::vector<Tri>& faces);

}  // namespace medax::msd::refine
