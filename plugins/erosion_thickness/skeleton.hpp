#pragma once
// Shape-revealing, topology-preserving skeletons (Yan et al. 2016, §7.3; notes §6).
//
// The refined complex K is the paper's cell complex: every triangle is cut by the burn arcs into
// faces (medial_curves.hpp) and every face by its medial-curve edges (spokes from the face's dual
// point) into wedges. 2-cells: the wedges (a face with a single spoke is one 2-cell whose boundary
// runs through the spoke twice; it cannot collapse through it); 1-cells: the pieces of the
// segments (split at used dual points), the chords (burn arcs across a triangle), the spokes and
// the input's edges that bound no triangle; 0-cells: graph nodes and dual points. A pair (sigma,
// tau) is free when sigma appears once in the boundary of tau and in no other surviving cell.
//
// Priorities: a wedge gets the mean ET_M over the graph-node corners of its face; a medial-curve
// 1-cell the mean ET_C of its ends; every other cell -inf. Protected: wedges with priority >
// theta2 and curve 1-cells with priority > theta1, minus connected components (wedges sharing a
// 1-cell; curve 1-cells sharing a point) of area < phi2 or length < phi1. Then the contraction
// of Liu et al. 2010 removes free pairs whose cells are outside the closure of the protected
// cells until none is left: the result is homotopy equivalent to the input and contains every
// protected cell. Order: first every pair that involves no medial-curve cell, in ascending
// (prio tau, prio sigma); then the pairs that cut or prune the curves, in the same order (so what
// survives to keep the topology follows C, and C's branches are pruned from low ET_C to high).
//
// Output (a MedialComplex needs triangles): surviving wedges as fans from their face's dual
// point; input triangles whose wedges all survive are written as themselves, or as a fan from
// their centre when a neighbour needs the points on their sides.
#include "medial_curves.hpp"

#include <cstddef>
#include <vector>

namespace medax::et {

/// Thresholds in the complex's units. The et_skeleton stage binds these fields as its parameters,
/// as fractions of the reference length L (the defaults are the paper's on a unit box), and
/// passes theta × L, phi2 × L², phi1 × L to compute_skeleton.
struct SkeletonOptions {
  double theta2 = 0.02;   ///< ET_M threshold for sheets
  double theta1 = 0.04;   ///< ET_C threshold for curves
  double phi2 = 0.0005;   ///< area below which protected sheet components are dropped
  double phi1 = 0.0;      ///< length below which protected curve components are dropped
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
  std::vector<double> face_priority;         ///< mean ET_M of the paper face (area-weighted when coarsened)

  // Statistics.
  std::size_t refined_vertices = 0, refined_edges = 0, refined_faces = 0;  ///< cells of K (faces: wedges)
  std::size_t protected_faces = 0, protected_curve_edges = 0;  ///< wedges, curve 1-cells
  double protected_area = 0;
  std::size_t dropped_sheet_components = 0, dropped_curve_components = 0;
  std::size_t coarse_triangles = 0;  ///< input triangles written whole (as one triangle or a fan)
  double seconds_refine = 0, seconds_protect = 0, seconds_contract = 0, seconds_output = 0;  ///< K built; protection; protection + collapse; output
};

/// `loose_edges`: edges of the input complex that bound no triangle (vertex ids of the
/// complex, which are graph nodes 0..V-1).
Skeleton compute_skeleton(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                          const SkeletonOptions& options);

}  // namespace medax::et
