#pragma once
// Internal to the MSD skeleton construction, step c: the restricted Delaunay triangulation, from
// the cells touching each split vertex, and its thinning.
#include "construction_split.hpp"

#include <set>

namespace medax::msd {

/// The dual complex of the split: an edge per pair of touching cells, triangles for three or more.
struct Rdt {
  std::set<Segment> edges;
  std::set<Tri> triangles;
};

Rdt dual_complex(const SplitMesh& split, const std::vector<Vec3>& sites, ConstructionStats& stats);
/// MATFP thinning: while the triangles close a tetrahedron, delete its smallest free face (a
/// face of exactly one closed tetrahedron), which opens the tetrahedron without a new hole.
std::size_t thin_tetrahedra(Rdt& rdt, const std::vector<Vec3>& points);

}  // namespace medax::msd
