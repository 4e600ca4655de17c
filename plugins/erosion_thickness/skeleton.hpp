#pragma once
// Shape-revealing, topology-preserving skeletons (Yan et al. 2016, §7.3; notes §6).
//
// The refined complex K is simplicial: every face of the subdivision (medial_curves.hpp) is
// fanned from its dual point over its corners and the dual points of its used segments, so the
// medial-curve edges (face dual -> segment dual) are edges of K and every paper face is the union
// of its fan triangles, which share its priority. Edges of the input that bound no triangle and
// isolated vertices are kept as they are (priority -inf; they collapse like any free cell).
//
// Output: input triangles that survive whole are written as themselves, or as a fan from their
// centre when a neighbour needs the points on their sides; the rest as the refined cells.
//
// Priorities: a fan triangle gets the mean ET_M over the graph-node corners of its face; an edge
// of C the mean ET_C of its ends; every other cell -inf. Protected: triangles with priority >
// theta2 and curve edges with priority > theta1, minus connected components (edge-adjacent
// triangles; vertex-adjacent curve edges) of area < phi2 or length < phi1. Then the contraction
// of Liu et al. 2010 removes simple pairs (sigma, tau) - tau maximal, sigma's only coface, both
// outside the closure of the protected cells - until none is left: the result is homotopy
// equivalent to the input and contains every protected cell. Order: first every pair that
// involves no medial-curve edge, in ascending (prio tau, prio sigma); then the pairs that cut or
// prune the curves, in the same order (so what survives to keep the topology follows C, and C's
// branches are pruned from low ET_C to high).
#include "medial_curves.hpp"

#include <cstddef>
#include <vector>

namespace medax::et {

struct SkeletonOptions {
  double theta2 = 0.02;   ///< absolute ET_M threshold for sheets
  double theta1 = 0.04;   ///< absolute ET_C threshold for curves
  double phi2 = 0.0005;   ///< absolute area below which protected sheet components are dropped
  double phi1 = 0.0;      ///< absolute length below which protected curve components are dropped
  bool coarsen = true;    ///< write input triangles that survive whole as themselves (see compute_skeleton)
};

struct Skeleton {
  std::vector<Vec3> points;
  std::vector<double> radius, bt, et, et_c;  ///< et_c is NaN off the medial curves
  std::vector<int> kind;  ///< 0 vertex, 1 edge sample, 2 segment dual, 3 face dual, 4 centre of a coarsened triangle
  std::vector<Segment> edges;                ///< every remaining edge (triangle sides included)
  std::vector<int> edge_curve;               ///< 1 for edges of the medial curves
  std::vector<double> edge_priority;         ///< ET_C mean for curve edges, -inf otherwise
  std::vector<Tri> faces;
  std::vector<double> face_priority;         ///< mean ET_M of the paper face

  // Statistics.
  std::size_t refined_vertices = 0, refined_edges = 0, refined_faces = 0;
  std::size_t protected_faces = 0, protected_curve_edges = 0;
  std::size_t dropped_sheet_components = 0, dropped_curve_components = 0;
  std::size_t coarse_triangles = 0;  ///< input triangles written whole (as one triangle or a fan)
  double seconds_refine = 0, seconds_fans = 0, seconds_protect = 0, seconds_contract = 0, seconds_output = 0;
};

/// `loose_edges`: edges of the input complex that bound no triangle (vertex ids of the
/// complex, which are graph nodes 0..V-1).
Skeleton compute_skeleton(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                          const SkeletonOptions& options);

}  // namespace medax::et
