// Signed distances to single envelope primitives (exact closed forms: envelope_primitives.hpp).
#include "envelope_primitives.hpp"

#include <medax/services/envelope.hpp>

namespace medax::services {

using envelope_detail::make_prim;

double sphere_signed_distance(const Vec3& x, const Vec3& c, double r) { return envelope_detail::sphere_value(x, c, r); }

double cone_signed_distance(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1) {
  return make_prim(2, {c0, c1, c1}, {r0, r1, r1}).value(x);
}

double slab_signed_distance(const Vec3& x, const Vec3& c0, double r0, const Vec3& c1, double r1, const Vec3& c2,
                            double r2) {
  return make_prim(3, {c0, c1, c2}, {r0, r1, r2}).value(x);
}

}  // namespace medax::services
