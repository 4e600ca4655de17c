#pragma once
// Q-MAT's flip test (notes §1.4): does moving both ends of edge (i, j) to a new centre turn the
// normal of a face around them (one that does not vanish, i.e. does not hold both) by more
// than 90°? Each evaluation of an edge tests up to four candidate centres, and the edges of a
// merged vertex are evaluated one after another, so the faces around a vertex are gathered
// once into a "fan" (its two other corners and the face's current normal, slivers left out)
// and kept until the mesh changes. The arithmetic is the same as testing face by face.
#include "collapse_mesh.hpp"

#include <array>
#include <vector>

namespace medax::qmat {

class FlipTest {
 public:
  explicit FlipTest(const CollapseMesh& mesh) : mesh_(mesh) {}

  /// Whether moving i and j to `centre` flips a face around them.
  bool flips(Index i, Index j, const Vec3& centre);
  /// Drops the gathered fans; call after every change of the mesh or of a sphere.
  void forget() { slots_[0].vertex = slots_[1].vertex = kNone; }

 private:
  static constexpr Index kNone = static_cast<Index>(-1);
  struct Corner {
    Vec3 a, b, normal;  ///< the face's other corners (in face order after v) and its normal
    Index va, vb;
  };
  struct Fan {
    Index vertex = kNone;
    std::vector<Corner> corners;
  };
  const Fan& fan_of(Index v);
  static bool any_flip(const Fan& fan, Index other, const Vec3& centre);

  const CollapseMesh& mesh_;
  std::array<Fan, 2> slots_;
  int next_slot_ = 0;  // the slot a new fan replaces (the other holds the last one used)
};

}  // namespace medax::qmat
