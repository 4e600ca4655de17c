#pragma once
// The inner/outer selection of MEDIAL's facets (notes §2.6): which selected Delaunay edges are
// "enclosed by" the surface. Internal to the dey_zhao package.
#include <medax/services/delaunay.hpp>
#include <medax/surface.hpp>

#include <memory>
#include <vector>

namespace medax::dey_zhao {

/// (a) When every mesh triangle is a Delaunay facet (the paper's TIGHT COCONE surface is a
/// subcomplex of Del(P)): each cell is labelled by the parity of the mesh triangles crossed on a
/// walk from outside the convex hull (1 inside). `points` must be the mesh vertices, so that
/// mesh and Delaunay share indices. Returns false, with `missing` = the number of mesh triangles
/// that are not Delaunay facets, when the labels cannot be computed that way.
/// Throws std::invalid_argument when the triangles are Delaunay facets but do not close (the
/// parity is then inconsistent).
bool label_cells_by_surface(const services::DelaunayTetrahedralization& dt, const SurfaceMesh& mesh,
                            std::vector<char>& inside, std::size_t& missing);

/// (b) A closed mesh: an edge (p, q) is inner when its midpoint is strictly inside (exact ray
/// parity) and the segment, shrunk by 1/16 of its length at both ends, does not meet the mesh
/// (SegmentMeshTest: a box hierarchy and exact predicates).
class MeshEdgeSide {
 public:
  /// Throws std::invalid_argument when the mesh is not closed.
  explicit MeshEdgeSide(const SurfaceMesh& mesh);
  ~MeshEdgeSide();
  MeshEdgeSide(MeshEdgeSide&&) noexcept;
  MeshEdgeSide& operator=(MeshEdgeSide&&) noexcept;

  /// For each (p, q): 1 when inner.
  std::vector<char> inner(const std::vector<Vec3>& points, const std::vector<std::array<Index, 2>>& edges,
                          bool parallel = true) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace medax::dey_zhao
