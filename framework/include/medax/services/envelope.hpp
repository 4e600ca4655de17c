#pragma once
// The envelope of a medial complex: the union E of a sphere per vertex, a medial cone (convex
// hull of two spheres) per edge and a medial slab (convex hull of three spheres) per triangle,
// as Q-MAT, VMAS and MSD reconstruct a shape from its medial mesh.
//
// Every primitive P is the union of the balls B(c(λ), r(λ)) whose centre and radius interpolate
// its vertices' linearly (λ barycentric on the element), so its signed distance is
//     sd_P(x) = min_λ ( |x − c(λ)| − r(λ) ),
// a convex problem that is solved in closed form here (no sampling of λ). sd_P is the exact
// signed distance to ∂P outside P, and inside P whenever every interpolated ball touches ∂P (a
// proper cone or slab); for a degenerate slab (one sphere swallowing part of another) the inside
// value is a lower bound on the depth.
//
// The envelope function φ(x) = min_P sd_P(x) is therefore the exact distance from x to E when x
// is outside E (φ > 0), negative inside, and zero exactly on ∂E. Inside E, −φ is the deepest
// penetration into a single primitive, a lower bound on the distance to ∂E (the union can be
// deeper than any of its parts); boundary_distances() gives the distance to ∂E itself.
//
// Only maximal elements count as primitives: a slab contains the cones of its sides and a cone
// its two spheres, so edges that bound a triangle and vertices used by an edge or a triangle
// add nothing to the union and are skipped.
#include <medax/medial_complex.hpp>

#include <array>
#include <functional>
#include <memory>
#include <vector>

namespace medax::services {

/// One primitive of the envelope: a sphere (1 vertex), a cone (2) or a slab (3).
struct EnvelopePrimitive {
  int count = 1;                      ///< number of distinct vertices: 1 sphere, 2 cone, 3 slab
  std::array<Index, 3> vertices{};    ///< its medial vertices (the first `count` are used)
  Element element = Element::Vertex;  ///< the element it comes from (a face with a repeated
  Index index = 0;                    ///< vertex gives a cone) and that element's index
};

/// The primitive realising φ at a point, and the interpolated ball that does it.
struct EnvelopeHit {
  double distance = 0;        ///< φ(x): signed, negative inside
  Vec3 centre = Vec3::Zero(); ///< c(λ*) on the element (the closest point of P is centre + radius·n)
  double radius = 0;          ///< r(λ*)
  Index primitive = 0;        ///< index into Envelope::primitives()
};

/// Points on the boundary of the envelope with outward normals and the area each stands for.
struct EnvelopeSamples {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  std::vector<double> areas;  ///< sums to an estimate of the area of ∂E
  std::vector<Index> primitives;  ///< the primitive (index into Envelope::primitives()) each lies on
  double step = 0;            ///< grid step used

  std::size_t size() const { return points.size(); }
  double total_area() const;
};

/// Polled by the long envelope computations (from any thread, every few hundred work items) so a
/// caller can stop them: whatever it throws (e.g. Context::check_cancelled's Cancelled) ends the
/// call and propagates. Empty: never polled.
using CancelCheck = std::function<void()>;

/// Signed distances to single primitives (exact closed forms; see the file comment).
double sphere_signed_distance(const Vec3& x, const Vec3& c, double r);
double cone_signed_distance(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1);
double slab_signed_distance(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1,
                            const Vec3& c2, double r2);

class Envelope {
 public:
  /// Builds the primitives and a bounding-volume hierarchy over them. Copies what it needs:
  /// the complex may go away afterwards. Faces or edges with a repeated vertex are treated as
  /// the lower-dimensional element they really are.
  explicit Envelope(const MedialComplex& medial);
  ~Envelope();
  Envelope(Envelope&&) noexcept;
  Envelope& operator=(Envelope&&) noexcept;

  const std::vector<EnvelopePrimitive>& primitives() const;
  bool empty() const { return primitives().empty(); }
  /// Bounding box of the envelope (all balls).
  std::pair<Vec3, Vec3> bounds() const;

  /// φ(x) = min over primitives of sd_P(x).
  double signed_distance(const Vec3& x) const;
  /// φ(x) with the primitive and interpolated ball realising it.
  EnvelopeHit closest(const Vec3& x) const;
  /// φ at many points, in parallel.
  std::vector<double> signed_distances(const std::vector<Vec3>& points) const;
  /// The same by brute force over every primitive (tests, tiny complexes).
  double signed_distance_brute_force(const Vec3& x) const;

  /// Points on ∂E at resolution `step`, one per edge of a regular grid of spacing `step`
  /// (turned by a fixed generic rotation) whose ends lie on opposite sides of ∂E: the closest
  /// point of E to the edge's outside end, which lies exactly on ∂E. The grid edges near ∂E are
  /// found by octree refinement (φ is 1-Lipschitz) without evaluating φ far from ∂E. A point's
  /// area is step² / ‖n‖₁ (n its unit normal in the grid's frame): a plane with normal n cuts
  /// ‖n‖₁ grid edges per step² of area, so the areas sum to the boundary area and weight means
  /// by area. Parts of E thinner than `step` may fall between grid points and be missed.
  /// `progress` (optional) receives fractions in [0, 1], on the calling thread.
  EnvelopeSamples sample_boundary(double step, const std::function<void(double)>& progress = {},
                                  const CancelCheck& cancel = {}) const;

  /// Unsigned distance from each point to the boundary ∂E. Outside E: φ(x), exact. Inside E:
  /// −φ(x) (the depth into the deepest primitive) when the closest point of that primitive's
  /// boundary is on ∂E (no other primitive covers it), which makes it exact; otherwise the
  /// distance to the nearest of `samples`, an upper bound that exceeds the true distance by at
  /// most the samples' covering radius (≈ step), never below the lower bound −φ(x).
  /// With `refine_step` below the samples' step, those uncertified points also look at the
  /// boundary points of a grid of spacing max(refine_step, samples.step / 4) around them (the
  /// grid sample_boundary would use at that step, only within the current bound), so their
  /// bound is within that finer grid's covering radius; 0 (or ≥ samples.step): no refinement.
  /// `signed_distances` (optional) receives φ at the points, which the call computes anyway.
  std::vector<double> boundary_distances(const std::vector<Vec3>& points, const EnvelopeSamples& samples,
                                         std::vector<double>* signed_distances = nullptr,
                                         const CancelCheck& cancel = {}, double refine_step = 0) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace medax::services
