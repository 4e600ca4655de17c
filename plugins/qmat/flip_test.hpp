#pragma once
// Q-MAT's flip test (notes §1.4): does moving both ends of edge (i, j) to a new centre turn the
// normal of a face around them (one that does not vanish, i.e. does not hold both) by more
// than 90°? Each evaluation of an edge tests up to four candidate centres, and the edges of a
// merged vertex are evaluated one after another, so the faces around a vertex are gathered
// into a "fan" (its two other corners and the face's current normal, slivers left out) that is
// kept until the mesh changes, in a small cache of fans indexed by vertex (the first costing of
// all edges meets each vertex's fan from several edges). The fans' corners are carved one after
// another from one arena that starts over when the mesh changes (or when it is full), so the
// few fans of a collapse lie together in cache. A fan is gathered lazily, face by face,
// only as far as a test needs (most tests stop at the first flipping face), and the face that
// flipped last is tested first. The answer does not depend on the order; the arithmetic is that
// of testing face by face.
#include "collapse_mesh.hpp"

#include <cstdint>
#include <vector>

namespace medax::qmat {

class FlipTest {
 public:
  explicit FlipTest(const CollapseMesh& mesh) : mesh_(mesh) {}

  /// Whether moving i and j to `centre` flips a face around them.
  bool flips(Index i, Index j, const Vec3& centre);
  /// Drops the gathered fans; call after every change of the mesh or of a sphere.
  void forget() {
    ++epoch_;
    used_ = 0;
  }

 private:
  static constexpr Index kNone = static_cast<Index>(-1);
  struct Corner {
    Corner() {}  // left uninitialised: the arena grows without zeroing what gathering fills
    Vec3 a, b, normal;  ///< the face's other corners (in face order after v) and its normal
    Index va, vb;
  };
  struct Fan {
    Index vertex = kNone;
    std::uint64_t epoch = 0;      ///< the fan is current while this is the test's epoch
    std::size_t next_face = 0;    ///< position in the vertex's face list gathered up to
    std::size_t first = 0;        ///< its corners are corners_[first, first + count)
    std::size_t count = 0;
  };
  Fan& fan_of(Index v);
  /// Whether the face of corner c (around the moving end) turns by more than 90° when that end
  /// goes to `centre`; a face holding the edge's other end vanishes and is not tested.
  static bool turns(const Corner& c, Index other, const Vec3& centre) {
    return c.va != other && c.vb != other && c.normal.dot((c.a - centre).cross(c.b - centre)) < 0;
  }
  bool any_flip(Fan& fan, Index other, const Vec3& centre);
  bool gather_until_flip(Fan& fan, Index other, const Vec3& centre);

  static constexpr std::size_t kSlots = 256;             // fans kept, at slot vertex % kSlots
  static constexpr std::size_t kArenaCorners = 1024;  // the arena starts over beyond this (80 KiB: in L2)

  const CollapseMesh& mesh_;
  std::vector<Fan> slots_ = std::vector<Fan>(kSlots);
  std::vector<Corner> corners_;  // the arena
  std::size_t used_ = 0;         // corners_[0, used_) belong to current fans
  std::uint64_t epoch_ = 1;
};

}  // namespace medax::qmat
