#pragma once
// The "volume centres of the largest uncovered regions" of the MSD's incremental schedule
// (paper §5.3, Alg. 1; notes §2.7, §9.5 [C]): S is tetrahedralised once (TetGen), a tet is
// uncovered when its centroid lies in no primitive, uncovered tets are grouped by face adjacency
// and the groups ranked by volume. TetGen stays in the .cpp.
#include "primitive.hpp"

#include <medax/surface.hpp>

#include <string>
#include <vector>

namespace medax::msd {

/// A tetrahedralisation of the solid bounded by S, reduced to what the ranking needs.
struct SolidTets {
  std::vector<Vec3> centroids;
  std::vector<double> volumes;
  std::vector<std::array<int, 4>> neighbours;  ///< face-adjacent tets, -1 on the boundary
  std::size_t size() const { return centroids.size(); }
};

/// Tetrahedralises the closed surface with TetGen and `switches` ("pq1.05" in the authors'
/// code; "Q" and "n" are added). Throws std::runtime_error with TetGen's complaint when it fails.
SolidTets tetrahedralize_solid(const SurfaceMesh& surface, const std::string& switches);

/// One face-connected group of uncovered tets.
struct UncoveredRegion {
  double volume = 0;
  Vec3 centre = Vec3::Zero();  ///< volume-weighted mean of the tets' centroids
  std::size_t tets = 0;
};

/// The uncovered regions given which tets are covered (`covered[t]` != 0), largest volume first
/// (ties to the region holding the lowest tet).
std::vector<UncoveredRegion> uncovered_regions(const SolidTets& tets, const std::vector<char>& covered);

}  // namespace medax::msd
