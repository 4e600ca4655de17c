#pragma once
// Burn on a 1D graph: the 2D-shape erosion thickness of Liu et al. 2011 (Eq. 1), used by Yan et
// al. 2016 for ET on the medial curves (Eq. 8-9, notes §5.3). Fire starts at each leaf y
// (degree <= 1) at time ignite(y) and moves at unit speed along the edges; a vertex of degree d
// burns when d-1 of its edges have burned, i.e. at its (d-1)-th earliest arrival. Vertices on
// cycles (and those marked `anchored`, which never burn) keep +inf.
#include <medax/geometry.hpp>

#include <vector>

namespace medax::et {

struct Graph1D {
  std::vector<Vec3> points;
  std::vector<Segment> edges;
  std::vector<double> ignite;    ///< per vertex: ignition time if it is a leaf (BT_M for ET_C, R for 2D ET)
  std::vector<char> anchored;    ///< optional, per vertex: attached to an unburnable part, never burns
};

/// Burn time per vertex (+inf when never burned). Edges of zero length are allowed; self-loops
/// count twice in the degree as usual and never burn.
std::vector<double> burn_1d(const Graph1D& graph);

/// Brute force of Eq. (1) on a tree, for tests: BT(x) = max over leaf pairs (y, z) whose path
/// contains x of min(ignite(y) + d(x, y), ignite(z) + d(x, z)); a leaf x also has the pair (x, x)
/// (its own ignition). O(V^3).
std::vector<double> burn_1d_brute_force(const Graph1D& tree);

}  // namespace medax::et
