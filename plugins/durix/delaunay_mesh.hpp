#pragma once
// Conversion of a closed manifold triangle mesh into a Delaunay mesh (every triangle a facet of
// the 3D Delaunay tetrahedralization of the vertices), by edge flips and splits in the manner of
// Dyer, Zhang and Möller 2007 ("Delaunay mesh construction"), with incremental CGAL insertion.
// CGAL stays inside delaunay_mesh.cpp.
#include <medax/surface.hpp>

#include <cstddef>
#include <functional>
#include <string>

namespace medax::durix {

struct DelaunayMeshOptions {
  /// Flip a non-Delaunay edge only when its two faces make a dihedral angle below this (degrees)
  /// and the new edge is Delaunay; otherwise split it.
  double feature_angle_deg = 20.0;
  /// Allow flips at all (false: splits only; the geometry is then never changed).
  bool flips = true;
  /// Give up when more than max_insertions_factor * #vertices + 1000 points were inserted.
  double max_insertions_factor = 4.0;
  /// Give up after this many sweeps over all edges and faces.
  int max_sweeps = 100;
};

struct DelaunayMeshReport {
  std::size_t input_vertices = 0, input_faces = 0;
  std::size_t non_delaunay_edges_before = 0, non_delaunay_faces_before = 0;
  std::size_t flips = 0, edge_splits = 0, face_splits = 0, sweeps = 0;
  std::size_t output_vertices = 0, output_faces = 0;
  double seconds = 0;         ///< whole conversion, verification included
  double seconds_verify = 0;  ///< the final check on a fresh tetrahedralization
};

/// The result of checking a mesh against a fresh Delaunay tetrahedralization of its vertices.
struct DelaunayCheck {
  std::size_t faces = 0;
  std::size_t non_delaunay_faces = 0;  ///< faces that are not Delaunay facets
  std::size_t duplicate_points = 0;    ///< vertices at the position of an earlier vertex
  long long first_bad_face = -1;
  bool ok() const { return non_delaunay_faces == 0 && duplicate_points == 0; }
  std::string describe() const;
};

/// Builds the Delaunay tetrahedralization of the mesh vertices from scratch and tests every face.
DelaunayCheck check_delaunay_mesh(const SurfaceMesh& mesh);

/// Converts `mesh` (closed, 2-manifold, consistently oriented, no duplicate vertices; checked by
/// the caller) into a Delaunay mesh. The input vertices keep their indices; inserted vertices
/// follow. Flips move the surface slightly (within the feature angle); splits do not. The
/// result is always verified on a fresh tetrahedralization; throws std::runtime_error with a
/// clear message when the conversion does not finish or does not verify.
SurfaceMesh make_delaunay_mesh(const SurfaceMesh& mesh, const DelaunayMeshOptions& options = {},
                               DelaunayMeshReport* report = nullptr,
                               const std::function<void()>& check_cancelled = {});

}  // namespace medax::durix
