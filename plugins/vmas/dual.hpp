#pragma once
// Connectivity as the dual of the partition (notes §2.11): two spheres are adjacent when some
// graph edge (mesh edge, or kNN edge for clouds) joins their clusters; skeleton edges are the
// adjacent pairs and skeleton triangles the 3-cliques {a < b < c}.
#include <medax/geometry.hpp>

#include <string>
#include <utility>
#include <vector>

namespace medax::vmas {

/// Sorted neighbour lists of the clusters (sphere indices 0 .. count−1).
using Adjacency = std::vector<std::vector<Index>>;

/// Adjacency of the clusters: for each graph edge (u, w) with valid, different cluster_of.
Adjacency cluster_adjacency(const std::vector<Segment>& graph_edges, const std::vector<int>& cluster_of,
                            std::size_t count);

enum class TriangleRule {
  Cliques,     ///< the paper: every 3-clique of the adjacency
  Restricted,  ///< not in the paper: only cliques realised by a surface triangle whose three
               ///< vertices lie in the three clusters (meshes only)
  None,        ///< edges only
};

/// The name of each rule, as the `vmas_dual` stage's `triangles` parameter spells it.
inline const std::vector<std::pair<std::string, TriangleRule>> kTriangleRules{
    {"cliques", TriangleRule::Cliques}, {"restricted", TriangleRule::Restricted}, {"none", TriangleRule::None}};

struct DualComplex {
  std::vector<Segment> edges;  ///< i < j, sorted
  std::vector<Tri> faces;      ///< a < b < c, sorted
};

/// Edges and triangles of the dual. `triangles` (mesh faces) is needed only for Restricted.
DualComplex dual_complex(const Adjacency& adjacency, TriangleRule rule, const std::vector<Tri>& triangles = {},
                         const std::vector<int>& cluster_of = {});

}  // namespace medax::vmas
