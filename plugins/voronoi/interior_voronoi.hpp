#pragma once
// The interior Voronoi diagram of surface points: the raw discrete medial axis that Q-MAT,
// Erosion Thickness and most methods start from (Amenta, Choi & Kolluri 2001; Attali &
// Lachaud 2001). Plain C++ over the medax data model; the `voronoi` stage is a thin face of it.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <string>
#include <vector>

namespace medax::voronoi {

/// How circumcentres are classified. The two mesh tests are exact and give the same answer;
/// Normals serves point clouds, which have no mesh.
enum class InsideMethod {
  RayGrid,     ///< parity of +x rays over a (y, z) grid of the triangles (fast; medax::services::RayParityInside)
  SideOfMesh,  ///< CGAL::Side_of_triangle_mesh (medax::services::InsideTest), the reference
  Normals,     ///< the side of the cell's corners' oriented normals (pole labelling; no mesh)
};

/// Face label: the number of the Voronoi polygon each triangle belongs to (consecutive in
/// output order).
inline const Property<int> kPolygon{Element::Face, "polygon"};
/// Edge label: 1 for a fan diagonal, 0 for a Voronoi edge (the Voronoi edges come first).
inline const Property<int> kFanDiagonal{Element::Edge, "fan_diagonal"};

enum class Connectivity {
  Faces,  ///< Voronoi edges and fan-triangulated Voronoi faces
  Edges,  ///< Voronoi edges only
  None,   ///< the medial spheres only
};

struct InteriorVoronoiOptions {
  InsideMethod inside = InsideMethod::RayGrid;
  Connectivity connectivity = Connectivity::Faces;
  std::string generator_kind = "mesh_vertex";  ///< what the point indices refer to
  bool parallel = true;
};

/// What the extraction did, for logs and benchmarks.
struct InteriorVoronoiReport {
  std::size_t points = 0;         ///< distinct points in the Delaunay tetrahedralization
  std::size_t cells = 0;          ///< finite Delaunay cells
  std::size_t interior = 0;       ///< cells whose circumcentre is strictly inside
  std::size_t voronoi_edges = 0;  ///< edges dual to Delaunay facets (the rest are fan diagonals)
  std::size_t voronoi_faces = 0;  ///< polygons dual to Delaunay edges, before triangulation
  double seconds_delaunay = 0;    ///< Delaunay tetrahedralization (overlapping the inside-test setup)
  double seconds_inside = 0;      ///< classifying the circumcentres
  double seconds_complex = 0;     ///< compacting and building edges, faces, generators
};

/// The interior Voronoi diagram of `points` (surface samples of `mesh`, or its vertices):
/// - one medial vertex per Delaunay cell whose circumcentre is strictly inside `mesh`
///   (centre = circumcentre, radius = circumradius), in the Delaunay service's cell order;
/// - an edge between two such vertices when their cells share a facet (a Voronoi edge);
/// - for every Delaunay edge whose ring of cells is finite and all interior, its Voronoi
///   polygon, fan-triangulated from the ring's lowest cell; the fan diagonals are added to the
///   edges (edge label `fan_diagonal` = 1) and face label `polygon` numbers the polygons;
/// - generators: the 4 point indices of each vertex's cell (sorted), which are equidistant
///   from the centre at the radius.
/// Duplicate points are merged (the lowest index represents them). Deterministic: the same
/// input gives the same output, whatever the thread schedule.
/// Throws std::invalid_argument when the points span less than 3D or the mesh is not closed.
MedialComplex interior_voronoi(const std::vector<Vec3>& points, const SurfaceMesh& mesh,
                               const InteriorVoronoiOptions& options = {},
                               InteriorVoronoiReport* report = nullptr);

/// The same for oriented samples without a mesh (a point cloud): a cell is interior when its
/// circumcentre c lies on the inner side of its four corners p, sum of n_p · (c − p)/|c − p| < 0,
/// and within the points' bounding box (`options.inside` is not used). Throws std::invalid_argument without one normal per sample.
MedialComplex interior_voronoi(const OrientedSamples& samples, const InteriorVoronoiOptions& options = {},
                               InteriorVoronoiReport* report = nullptr);

}  // namespace medax::voronoi
