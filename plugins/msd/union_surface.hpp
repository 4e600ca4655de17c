#pragma once
// Ŝ = ∂(∪ T_P) without a grid (docs/plugins/msd.md, "Reconstruction Ŝ"): every primitive's
// triangles that lie outside all the other primitives, cut where they enter one. The signed-distance
// Ŝ (reconstruction.hpp) blurs everything below its voxel (1/256 of the box); this one keeps the
// primitives' own triangles, so a refined primitive's copy of S's triangles stays exact and ε̄¹ can
// reach 0, which the paper's error figures (libigl's exact booleans) need.
#include <medax/reconstructed_surface.hpp>

#include <vector>

namespace medax::msd {

struct UnionOptions {
  /// A point is inside another primitive when it is on its bounded side and farther than this from
  /// its surface, in units of the longest bounding-box side of all primitives; points within it of
  /// a surface are on it (kept). The fitted T_P's chords lie up to ~5e-4 off S in concave parts, so
  /// neighbouring primitives' surfaces interleave at that depth; judged by their corners, two such
  /// surfaces would both be dropped and leave a hole. 1e-3 is the authors' selection distance.
  double tolerance = 1e-3;
};

/// The boundary of the union of closed, outward-oriented triangle meshes, as a triangle mesh in the
/// working frame (`to_input` copied into the result). Each triangle is judged against every other
/// solid whose box meets its solid's box, by where its corners are (outside, on the surface within
/// the tolerance, inside):
/// - a corner inside and a corner outside: clipped, each crossing edge cut where it enters the
///   solid (bisection to 1e-9 of the box), the outside part re-triangulated;
/// - corners outside or on, none inside: kept whole (a solid poking through its interior without
///   reaching a corner is missed);
/// - no corner outside: dropped when the centroid is inside, kept when all corners and the centroid
///   are on (a face the two share); with a corner inside and the centroid outside the triangle
///   leaves the solid between its corners, so it is halved at its edges' midpoints (twice at most)
///   and the quarters judged again, the last level keeping what it cannot decide; with a corner
///   inside and the centroid on the surface, dropped.
/// Vertices with equal coordinates are merged; of identical triangles one is kept, and a triangle
/// present in both orientations (two solids touching face to face) is dropped. The result is
/// watertight only where no cut was made: along the curves where solids cross, the pieces of the
/// two sides meet without sharing vertices. Deterministic, in parallel over the solids.
/// Throws std::invalid_argument when `solids` holds no face.
ReconstructedSurface reconstruct_union(const std::vector<SurfaceMesh>& solids, const Similarity& to_input,
                                       const UnionOptions& options = {});

}  // namespace medax::msd
