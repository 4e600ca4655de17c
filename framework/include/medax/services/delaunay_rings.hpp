#pragma once
// Rings of Delaunay cells around Delaunay edges: the Voronoi facet dual to an edge is the cycle of
// the circumcentres of the cells around it. Header-only and generic over how cells are stored
// (the DelaunayTetrahedralization arrays, or a caller's compact copy), so that the walk inlines
// into the caller's loop. Used by the voronoi and dey_zhao extractions.
#include <medax/geometry.hpp>

#include <vector>

namespace medax::services {

/// The six edges of a tetrahedron: the corner positions i, j of the edge, then the other two.
inline constexpr int kCellEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};

/// Sign of the permutation kCellEdges[e] of (0, 1, 2, 3): for a positively oriented cell, the
/// orientation of (corner i, corner j, corner k, corner l). When positive, the other two corners
/// a = corner k, b = corner l turn counter-clockwise from a to b about the edge i → j, and
/// crossing the facet opposite a walks around the edge counter-clockwise.
constexpr int cell_edge_sign(int e) {
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += kCellEdges[e][i] > kCellEdges[e][j];
  return inversions % 2 ? -1 : 1;
}

/// Position of `v` among a cell's corners (3 when it is not among the first three).
inline int corner_position(const std::array<Index, 4>& corner, Index v) {
  return corner[0] == v ? 0 : corner[1] == v ? 1 : corner[2] == v ? 2 : 3;
}

enum class RingEnd {
  Closed,    ///< back at the start cell: the ring is a cycle
  Boundary,  ///< the next cell is absent (infinite, or left out by the caller)
  Lower,     ///< the next cell is numbered below the start cell (or the ring is too long)
};

/// Walks around the Delaunay edge (u, w) from cell `start`, first across the facet opposite its
/// corner `cross` (`keep` is the cell's fourth corner), appending the cells after `start` to
/// `ring`. Stops back at `start` (Closed), before an absent neighbour (Boundary: `*last` and
/// `*last_facet` are then the last cell and the corner position whose facet leads out), or at a
/// cell numbered below `start` (Lower: `start` is not the lowest cell of the ring). `max_ring`
/// bounds the ring length (Lower beyond it).
/// `corners(c)` gives cell c's 4 corners (const std::array<Index, 4>&), `neighbour(c, k)` the
/// cell across the facet opposite corner k, equal to `absent` when there is none.
template <typename Cell, typename Corners, typename Neighbour>
RingEnd walk_edge_ring(Cell start, Index u, Index w, Index cross, Index keep, const Corners& corners,
                       const Neighbour& neighbour, Cell absent, std::vector<Cell>& ring,
                       std::size_t max_ring = ~std::size_t{0}, Cell* last = nullptr, int* last_facet = nullptr) {
  Cell current = start;
  for (;;) {
    const int k = corner_position(corners(current), cross);
    const Cell next = neighbour(current, k);
    if (next == start) return RingEnd::Closed;
    if (next == absent) {
      if (last) *last = current;
      if (last_facet) *last_facet = k;
      return RingEnd::Boundary;
    }
    if (next < start || ring.size() > max_ring) return RingEnd::Lower;
    ring.push_back(next);
    const auto& n = corners(next);
    Index fresh = n[0];
    for (Index v : n)
      if (v != u && v != w && v != keep) fresh = v;
    cross = keep;
    keep = fresh;
    current = next;
  }
}

}  // namespace medax::services
