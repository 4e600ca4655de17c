#include "flip_test.hpp"

#include <algorithm>
#include <utility>

namespace medax::qmat {

namespace {
constexpr double kSliver = 1e-6;  // sine of a face's angle below which it has no normal
}

/// v's fan, or a new empty one with room in the arena for all of v's faces (when the arena is
/// full, every fan is dropped and it starts over).
FlipTest::Fan& FlipTest::fan_of(Index v) {
  Fan& fan = slots_[v % kSlots];
  if (fan.vertex == v && fan.epoch == epoch_) return fan;
  const std::size_t room = mesh_.face_list(v).size();
  if (used_ + room > kArenaCorners && used_ > 0) forget();
  if (used_ + room > corners_.size()) corners_.resize(used_ + room);
  fan.vertex = v;
  fan.epoch = epoch_;
  fan.next_face = 0;
  fan.first = used_;
  fan.count = 0;
  used_ += room;
  return fan;
}

bool FlipTest::any_flip(Fan& fan, Index other, const Vec3& centre) {
  Corner* corners = corners_.data() + fan.first;
  for (std::size_t k = 0; k < fan.count; ++k)
    if (turns(corners[k], other, centre)) {
      std::swap(corners[0], corners[k]);  // the next candidate is likely to turn it too
      return true;
    }
  return gather_until_flip(fan, other, centre);
}

/// Gathers the fan's remaining faces, testing each as it comes, up to the first that turns.
/// Slivers (the Voronoi axis has many, from nearly coincident vertices) have no normal to turn
/// and are left out.
bool FlipTest::gather_until_flip(Fan& fan, Index other, const Vec3& centre) {
  const Index v = fan.vertex;
  const ListPool::View faces = mesh_.face_list(v);
  Corner* corners = corners_.data() + fan.first;
  const Vec3 p = centre_of(mesh_.spheres[v]);
  while (fan.next_face < faces.size()) {
    const Index f = faces[fan.next_face++];
    if (!mesh_.face_alive(f)) continue;
    const Tri& t = mesh_.face(f);
    const int at = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
    Corner& c = corners[fan.count];  // filled in place: the gathering is a hot loop
    c.va = t[(at + 1) % 3];
    c.vb = t[(at + 2) % 3];
    c.a = centre_of(mesh_.spheres[c.va]);
    c.b = centre_of(mesh_.spheres[c.vb]);
    const Vec3 e1 = c.a - p, e2 = c.b - p;
    c.normal = e1.cross(e2);
    if (!(c.normal.squaredNorm() > kSliver * kSliver * e1.squaredNorm() * e2.squaredNorm())) continue;
    const std::size_t k = fan.count++;
    if (turns(c, other, centre)) {
      std::swap(corners[0], corners[k]);
      return true;
    }
  }
  return false;
}

bool FlipTest::flips(Index i, Index j, const Vec3& centre) {
  for (Index end : {i, j}) {
    if (centre_of(mesh_.spheres[end]) == centre) continue;  // this end does not move
    if (any_flip(fan_of(end), end == i ? j : i, centre)) return true;
  }
  return false;
}

}  // namespace medax::qmat
