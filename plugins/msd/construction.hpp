#pragma once
// Construction of the Medial Skeletal Diagram's skeleton M_S = (V̂, Ê, F̂) from sites on the
// medial mesh M (Guo et al. 2024 §5.1; notes §3 S3 a–g):
//   a. restricted Voronoi labelling: every facet of M is clipped by the 3D (Euclidean) bisectors
//      of the sites, each convex piece belongs to its nearest site;
//   b. each cell is made one connected component: the component holding the site stays, every
//      orphan component goes to the neighbouring component whose site is nearest its centre;
//   c. RDT: a point of the split M touched by exactly 2 cells gives an edge, by exactly 3 a
//      triangle, by 4 or more a polygon (fan-triangulated in angular order); closed
//      tetrahedra are thinned (MATFP free-face removal, smallest area first);
//   d. cells sharing several separate interfaces get a polyline site → interface → site per
//      extra interface;
//   e. an edge that crosses S is bisected, the midpoint projected onto the M shortest path
//      between its endpoints, until no part crosses (or the depth limit is reached);
//   f. triangles whose sides were revised are re-triangulated as 3D polygons;
//   g. Ê keeps only edges that are no triangle side; degree-2 non-site vertices of a straight
//      chain (angle > collapse_angle) are removed when the replacing segment does not cross S.
#include "medial_mesh.hpp"

#include <medax/surface.hpp>

#include <array>
#include <memory>
#include <vector>

namespace medax::msd {

/// Exact intersection tests of segments and triangles with the surface S (CGAL AABB tree,
/// exact predicates). Build once per shape; queries are thread-safe.
class SurfaceCrossing {
 public:
  explicit SurfaceCrossing(const SurfaceMesh& surface);
  ~SurfaceCrossing();
  SurfaceCrossing(SurfaceCrossing&&) noexcept;
  SurfaceCrossing& operator=(SurfaceCrossing&&) noexcept;
  /// True when the closed segment ab meets a triangle of S.
  bool crosses(const Vec3& a, const Vec3& b) const;
  /// True when the closed triangle abc meets a triangle of S.
  bool crosses(const Vec3& a, const Vec3& b, const Vec3& c) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct ConstructionOptions {
  bool multi_interface = true;     ///< step d
  int max_bisection_depth = 12;    ///< step e: an edge is split into at most 2^depth parts
  double collapse_angle_deg = 179;  ///< step g
};

/// One piece of the restricted Voronoi diagram: a facet of M cut by the bisectors.
struct RvdPiece {
  Index facet = 0;            ///< the M facet (MedialMesh numbering)
  Index site = 0;             ///< the nearest site (step a)
  Index cell = 0;             ///< the site whose cell holds the piece after step b
  std::vector<Vec3> polygon;  ///< convex polygon (triangle facet) or 2 points (dangling edge)
  double measure = 0;         ///< area (triangle facet) or length (dangling edge)
  Vec3 centroid = Vec3::Zero();
};

struct ConstructionStats {
  std::size_t orphan_components = 0;    ///< relabelled in step b
  std::size_t polygons = 0;             ///< split points touching >= 4 cells (step c)
  std::size_t tetrahedra_thinned = 0;   ///< step c
  std::size_t extra_interfaces = 0;     ///< polylines added in step d
  std::size_t bisections = 0;           ///< vertices added in step e
  std::size_t unresolved_edges = 0;     ///< edges still crossing S at the depth limit
  std::size_t retriangulated = 0;       ///< triangles revised in step f
  std::size_t collapsed = 0;            ///< degree-2 vertices removed in step g
  std::size_t crossing_triangles = 0;   ///< triangles of F̂ that meet S (reported, not fixed)
};

struct Skeleton {
  /// V̂: the sites first (vertex i is site i), then the vertices added by steps d and e.
  std::vector<Vec3> vertices;
  std::vector<char> is_site;
  std::vector<Index> host_facet;  ///< the M facet holding each vertex
  std::vector<Segment> edges;     ///< Ê: unique edges, none a side of a triangle, (low, high)
  std::vector<Tri> triangles;     ///< F̂, each sorted ascending
  std::vector<RvdPiece> pieces;   ///< the split M with the cell of each piece
  ConstructionStats stats;
};

/// Steps a–g for `sites` (points on M; each is projected onto M first). Throws
/// std::invalid_argument when there is no site or two sites coincide.
Skeleton construct_skeleton(const MedialMesh& mesh, const std::vector<Vec3>& sites,
                            const SurfaceCrossing& surface, const ConstructionOptions& options = {});

/// Steps a–b only: the restricted Voronoi pieces of M with their (one-component) cells.
std::vector<RvdPiece> restricted_voronoi(const MedialMesh& mesh, const std::vector<Vec3>& sites);

/// The centroid c(RVC) of each cell (E_cent, notes §2.7): area-weighted over its triangle
/// pieces, or length-weighted over its dangling-edge pieces when it has no triangle piece.
/// A cell without pieces gets NaN.
std::vector<Vec3> cell_centroids(const std::vector<RvdPiece>& pieces, std::size_t num_sites);

}  // namespace medax::msd
