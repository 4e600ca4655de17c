#include "refine_snap.hpp"

#include "refine_topology.hpp"

namespace medax::msd::refine {

std::vector<char> snap_template_border(const Primitive& primitive, const std::vector<Tri>& remaining, double reach,
                                       PointSet& points) {
  const PrimitiveTemplate& shape = primitive.shape;
  std::vector<char> moved(shape.size(), 0);
  for (const auto& loop : border_loops(remaining).loops)
    for (Index v : loop) {
      if (!(primitive.max_radius[v] - primitive.radius[v] < reach)) continue;
      points.points[v].position = shape.base[v] + primitive.max_radius[v] * shape.direction[v];
      moved[v] = 1;
    }
  return moved;
}

}  // namespace medax::msd::refine
