#pragma once
// Coverage of S by fitted primitives (paper Eq. 8, E_cov; notes §2.7, §9.3): a vertex v of S is
// covered when some primitive has ℰ(v; T_P) < δ, and E_cov = −Σ_covered A(v) ∈ [−1, 0].
// ℰ(x; T_P) follows Eq. 3: p = cp(x; P), ℰ = ‖x − p‖ − r(d), with r(d) the distance from p along
// d = (x − p)/‖x − p‖ to T_P (the radial test; a consistent primitive is met once). The signed
// distance to T_P (sign from the same radial test) is the other choice. Each primitive keeps its
// own AABB tree and tests only the vertices near its bounding box; the coverage of a diagram is
// the union of its primitives' covered vertices, so a primitive whose fit is cached keeps its list.
#include "primitive.hpp"
#include "target_mesh.hpp"

#include <memory>
#include <vector>

namespace medax::msd {

enum class CoverageTest { Radial, SignedDistance };

struct CoverageOptions {
  /// δ of Eq. 8 in units of TargetMesh::scale() (the paper's unit box): 1e-4 in the paper; the
  /// authors' code effectively uses ℓ̄ (notes §9.3).
  double delta = 1e-4;
  CoverageTest test = CoverageTest::Radial;
};

/// One primitive's T_P with its AABB tree, for ℰ queries.
class PrimitiveShape {
 public:
  explicit PrimitiveShape(const Primitive& primitive);
  ~PrimitiveShape();
  PrimitiveShape(PrimitiveShape&&) noexcept;
  PrimitiveShape& operator=(PrimitiveShape&&) noexcept;

  /// ℰ(x; T_P) by the radial test (negative inside).
  double radial(const Vec3& x) const;
  /// Signed distance from x to T_P (negative inside).
  double signed_distance(const Vec3& x) const;
  /// True when x is within `margin` of T_P's bounding box (a cheap reject).
  bool near(const Vec3& x, double margin) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct Coverage {
  std::vector<char> covered;  ///< per vertex of S
  double energy = 0;          ///< E_cov = −Σ_covered A(v), in [−1, 0]
};

/// The vertices of S that one primitive covers (ℰ < δ), ascending; empty when it is not fitted.
/// Parallel over S's vertices, deterministic.
std::vector<Index> covered_vertices(const TargetMesh& target, const Primitive& primitive,
                                    const CoverageOptions& options = {});

/// The union of covered-vertex lists as a Coverage of S.
Coverage union_coverage(const TargetMesh& target, const std::vector<std::vector<Index>>& covered_lists);

/// Coverage of S by the fitted primitives (unfitted ones are skipped), deterministic.
Coverage coverage(const TargetMesh& target, const std::vector<Primitive>& primitives, const CoverageOptions& options = {});

}  // namespace medax::msd
