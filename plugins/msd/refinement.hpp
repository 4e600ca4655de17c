#pragma once
// Feature-preserving refinement of a fitted primitive (paper §5.4; notes §2.8): T_P is changed so
// that it reproduces exactly the part of S it covers, with S's own vertices and triangles there,
// while staying closed, 2-manifold and consistent (one radius per direction of the element).
// How (refine_*.hpp, one step each): select S's covered vertices and triangles by the authors'
// rules; keep the selected triangles that face away from their corners' element points (exact
// orientation), filling small holes; remove the template triangles whose vertices' rays meet that
// patch or whose vertices lie within cleanup_length of it, and those the patch vertices' rays
// meet; snap the template's border ring onto S along its directions; join each patch border to
// a template border by a band of consistent triangles (a dynamic programme on ∂P^ρ0); check the
// result (closed 2-manifold sphere, no self-intersection, wraps the element once) or retry with
// the failing border's ring of the patch removed. The patch triangles are S's triangles with
// S's coordinates copied, so matched vertices and edges are exact.
#include "primitive.hpp"
#include "target_mesh.hpp"

#include <medax/surface.hpp>

#include <string>
#include <vector>

namespace medax::msd {

struct RefineOptions {
  /// A vertex of S is selected when its distance to T_P is below this (authors' code: 1e-3).
  double select_distance = 1e-3;
  /// ... or when the segment from the element to it does not cross S and meets T_P within this
  /// many mean edge lengths ℓ̄ of it (authors' code: 2).
  double select_reach = 2;
  /// Clean-up (authors' code: 5e-3): template vertices closer than this to the imprinted patch
  /// are removed before the band is triangulated, so no band edge shorter than about this joins
  /// a template vertex to the patch (the authors collapse such edges afterwards).
  double cleanup_length = 5e-3;
  /// When the band between the patch and the template cannot be closed consistently, the patch
  /// loses the ring of triangles along the failing border and the join is retried, at most
  /// this many times.
  int shrink_retries = 16;
  /// Holes of the selected patch of at most this many S triangles (vertices the selection missed
  /// inside the covered region) are filled with S's triangles there when they are consistent.
  std::size_t hole_triangles = 64;
};
// Lengths are in the unit box (multiples of TargetMesh::scale()).

/// A refined primitive: a general closed mesh whose vertices keep the element point b_i they are
/// measured from, so consistency stays checkable.
struct RefinedPrimitive {
  SurfaceMesh mesh;                 ///< closed, 2-manifold, outward oriented, working frame
  std::vector<Vec3> base;           ///< b_i ∈ P per mesh vertex
  std::vector<Index> input_vertex;  ///< the S vertex a mesh vertex is, or kNotInput
  std::vector<Index> input_faces;   ///< the S triangles the mesh contains, ascending
  bool refined = false;             ///< false: `mesh` is the fitted T_P unchanged, `note` says why
  std::string note;
  std::vector<Index> selected_vertices;  ///< the S vertices step 1 selected, ascending
  /// The S triangles step 1 selected, ascending. input_faces is this set less the triangles that
  /// could not be joined consistently, plus those filling small holes of the selection.
  std::vector<Index> selected_faces;
  double seconds = 0;                    ///< wall time of this primitive's refinement
};

/// input_vertex of a mesh vertex that is no S vertex.
inline constexpr Index kNotInput = static_cast<Index>(-1);

/// Refines one fitted primitive (an unfitted one is returned empty with refined = false).
RefinedPrimitive refine_primitive(const Primitive& primitive, const TargetMesh& target,
                                  const RefineOptions& options = {});

/// Every primitive, in parallel; the result does not depend on the thread count.
std::vector<RefinedPrimitive> refine_primitives(const std::vector<Primitive>& primitives, const TargetMesh& target,
                                                const RefineOptions& options = {});

}  // namespace medax::msd
