#include "flip_test.hpp"

namespace medax::qmat {

namespace {
constexpr double kSliver = 1e-6;  // sine of a face's angle below which it has no normal
}

const FlipTest::Fan& FlipTest::fan_of(Index v) {
  for (int s = 0; s < 2; ++s)
    if (slots_[s].vertex == v) {
      next_slot_ = 1 - s;
      return slots_[s];
    }
  Fan& fan = slots_[next_slot_];
  next_slot_ = 1 - next_slot_;
  fan.vertex = v;
  fan.corners.clear();
  const Vec3 p = centre_of(mesh_.spheres[v]);
  mesh_.for_each_face(v, [&](Index f) {
    const Tri& t = mesh_.face(f);
    const int at = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
    Corner& c = fan.corners.emplace_back();  // filled in place: the gathering is the hot loop
    c.va = t[(at + 1) % 3];
    c.vb = t[(at + 2) % 3];
    c.a = centre_of(mesh_.spheres[c.va]);
    c.b = centre_of(mesh_.spheres[c.vb]);
    const Vec3 e1 = c.a - p, e2 = c.b - p;
    c.normal = e1.cross(e2);
    // A sliver (the Voronoi axis has many, from nearly coincident vertices) has no normal to flip.
    if (!(c.normal.squaredNorm() > kSliver * kSliver * e1.squaredNorm() * e2.squaredNorm())) fan.corners.pop_back();
  });
  return fan;
}

bool FlipTest::any_flip(const Fan& fan, Index other, const Vec3& centre) {
  for (const Corner& c : fan.corners)
    if (c.va != other && c.vb != other && c.normal.dot((c.a - centre).cross(c.b - centre)) < 0) return true;
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
