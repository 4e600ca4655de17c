#pragma once
// Shape partitioning (notes §2.3, eq. 8): every active vertex goes to the sphere of least
// E_v(m_j), lowest index on ties. Brute force over the spheres, parallel over the vertices:
// each vertex's choice is independent, so the result does not depend on the thread count.
// Exact pruning (a bound from the Euclidean term) and the incremental update after local
// changes both give the brute-force result.
#include "energy.hpp"

#include <vector>

namespace medax::vmas {

/// cluster_of[v] = argmin_j E_v(m_j), or −1 for inactive vertices (or when there is no sphere).
/// `hint` (optional, e.g. the previous partition; may be stale or out of range) only speeds
/// the search up: spheres that provably cannot beat the hinted one are not evaluated. The result
/// is the same with any hint or none. `cluster_of` may be `hint` itself. `quadrics`: the Q_v of
/// eq. 8 (nullptr: the input's, eq. 7; or vertex_normal_quadrics()).
void assign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                     std::vector<int>& cluster_of, const std::vector<int>* hint = nullptr,
                     const std::vector<PackedQuadric>* quadrics = nullptr);

/// The same partition as assign_vertices, updated instead of recomputed. `cluster_of` must be
/// the exact partition against `spheres` except those flagged in `moved` (changed or added since;
/// entries −1 or out of range are searched afresh). A vertex whose sphere did not move was at the
/// argmin among the unmoved spheres, so only the moved ones are tested against it: after a local
/// change the cost is O(N·|moved|) cheap bound tests instead of a search over all spheres.
void reassign_vertices(const VmasInput& in, const std::vector<Sphere>& spheres, double lambda,
                       const std::vector<char>& moved, std::vector<int>& cluster_of,
                       const std::vector<PackedQuadric>* quadrics = nullptr);

/// The clusters as lists: members of sphere i are members[offsets[i] .. offsets[i+1]), ascending.
struct Clusters {
  std::vector<Index> offsets{0};
  std::vector<Index> members;
  std::size_t count() const { return offsets.size() - 1; }
  std::size_t size(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  const Index* begin(std::size_t i) const { return members.data() + offsets[i]; }
};

/// Groups the vertices by cluster (counting sort: deterministic, O(N + M)).
Clusters group_clusters(const std::vector<int>& cluster_of, std::size_t sphere_count);

}  // namespace medax::vmas
