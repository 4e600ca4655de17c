#pragma once
// The remeshing route to a Delaunay mesh (notes §1.2 option 2): a restricted-Delaunay surface of
// the input's solid, from CGAL Mesh_3. The surface facets are facets of the Delaunay
// tetrahedralization of all Mesh_3 vertices, so their circumspheres are empty of those vertices,
// hence of the surface vertices alone: the result is a Delaunay mesh. The input vertices are NOT
// kept (the surface is resampled). CGAL stays inside remesh.cpp.
#include <medax/surface.hpp>

#include <stdexcept>

#include <cstddef>

namespace medax::durix {

struct RemeshOptions {
  /// Mesh_3 facet_size (upper bound on the radius of the surface Delaunay balls), as a multiple
  /// of the input's mean edge length. 0.85 gives about as many vertices as the input on
  /// organic meshes (measured: bunny 3301 -> 2780 at the default distance).
  double facet_size = 0.85;
  /// Mesh_3 facet_distance (distance between a facet's circumcentre and its surface Delaunay
  /// ball's centre), as a fraction of the bounding-box diagonal. It sets the vertex count of
  /// CAD meshes, whose unprotected sharp creases need many small facets.
  double facet_distance = 0.002;
  /// Mesh_3 facet_angle: lower bound on the facet angles (degrees; ≤ 30 for termination).
  double facet_angle_deg = 25.0;
  /// Loose cell criterion (radius-edge ratio); the cells are not part of the result.
  double cell_radius_edge_ratio = 4.0;
  /// Stop (and fail) at max_vertices_factor Mesh_3 vertices per input vertex + max_vertices_base.
  std::size_t max_vertices_factor = 10;
  std::size_t max_vertices_base = 100000;
  /// About this many input vertices (every k-th) seed the mesher on the surface.
  std::size_t initial_points = 1000;
};

/// The mesher did not finish: it reached its vertex cap or stopped on an internal error. Its
/// refinement is sensitive to the sizes, so another attempt at other sizes may succeed.
struct RemeshRefinementError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RemeshReport {
  double facet_size = 0, facet_distance = 0;  ///< absolute values used
  std::size_t mesh3_vertices = 0;             ///< vertices of the whole tetrahedral mesh
  std::size_t restricted_facets = 0;          ///< Mesh_3's surface facets (the result is the cells' boundary)
  std::size_t inside_cells = 0;
  std::size_t output_vertices = 0, output_faces = 0;
  double seconds = 0;
};

/// Remeshes the solid bounded by `mesh` (closed, manifold, outward; checked by the caller) with
/// Mesh_3 (no feature protection, no perturbation, no exudation, manifold facets; sequential,
/// seeded with input vertices, no random draw: deterministic) and returns the boundary of the cells inside, outward oriented, with
/// its vertices numbered in order of first use. Not verified here (see make_delaunay_surface).
SurfaceMesh remesh_restricted_delaunay(const SurfaceMesh& mesh, const RemeshOptions& options = {},
                                       RemeshReport* report = nullptr);

}  // namespace medax::durix
