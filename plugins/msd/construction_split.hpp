#pragma once
// Internal to the MSD skeleton construction (construction.cpp), steps a–b: M split by the
// restricted Voronoi diagram of the sites, one connected component per cell.
#include "construction.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <set>
#include <vector>

namespace medax::msd {

inline Segment sorted_pair(Index a, Index b) { return a < b ? Segment{a, b} : Segment{b, a}; }
inline Tri sorted_tri(Index a, Index b, Index c) {
  Tri t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// Restricted Voronoi pieces. Every vertex of a piece carries a symbolic key so that the
// same point of the split M gets the same key from every facet that sees it:
//   {0, v}            a vertex of M,
//   {1, e, i, j}      where bisector(i, j) crosses edge e of M,
//   {2, t, i, j, k}   the Voronoi vertex of sites i, j, k inside triangle t.
using Key = std::array<Index, 5>;
inline constexpr Index kNone = std::numeric_limits<Index>::max();

/// A restricted Voronoi piece with the keys of its corners.
struct Piece {
  RvdPiece rvd;
  std::vector<Key> keys;  ///< one per polygon corner, in order
};

/// The split M: its pieces and, per split vertex (key), the pieces touching it and its point.
struct SplitMesh {
  std::vector<Piece> pieces;
  std::map<Key, std::vector<Index>> key_pieces;  ///< the pieces touching each split vertex
  std::map<Key, Vec3> key_point;
};

/// Steps a–b on sites on M (projected); relabelled orphan components are counted in `stats`.
SplitMesh labelled_split(const MedialMesh& mesh, const std::vector<Vec3>& sites, ConstructionStats& stats);

/// The cells (sorted, unique) of the given pieces: those meeting at a split vertex.
std::vector<Index> cells_at(const SplitMesh& split, const std::vector<Index>& pieces);

}  // namespace medax::msd
