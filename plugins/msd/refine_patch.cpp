#include "refine_patch.hpp"

#include "refine_topology.hpp"

#include <algorithm>
#include <map>

namespace medax::msd::refine {
namespace {

/// The patch without the faces touching a vertex of `sorted_vertices`.
Patch without_faces_at(const Patch& patch, const std::vector<Index>& sorted_vertices) {
  Patch kept;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const Tri& t = patch.faces[f];
    if (std::any_of(t.begin(), t.end(), [&](Index v) {
          return std::binary_search(sorted_vertices.begin(), sorted_vertices.end(), v);
        }))
      continue;
    kept.faces.push_back(t);
    kept.input_face.push_back(patch.input_face[f]);
  }
  return kept;
}

/// Drops the faces around pinch vertices of the border until there is none (each pass removes
/// faces, so this ends).
void remove_pinches(Patch& patch) {
  while (!patch.faces.empty()) {
    const Borders borders = border_loops(patch.faces);
    if (borders.pinches.empty()) return;
    patch = without_faces_at(patch, borders.pinches);
  }
}

}  // namespace

PointSet template_points(const Primitive& primitive) {
  PointSet set;
  const PrimitiveTemplate& shape = primitive.shape;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    set.points.push_back({shape.base[i] + primitive.radius[i] * shape.direction[i], shape.base[i],
                          shape.base[i] + primitive.initial_radius * shape.direction[i]});
    set.input_vertex.push_back(kNoVertex);
  }
  return set;
}

Patch build_patch(const Primitive& primitive, const TargetMesh& target, const std::vector<Index>& selected,
                  PointSet& points) {
  const SurfaceMesh& s = target.mesh();
  std::map<Index, Index> point_of;  // S vertex → point id
  const auto add = [&](Index v) -> Index {
    const auto it = point_of.find(v);
    if (it != point_of.end()) return it->second;
    const Framing framing = frame_point(primitive.element, primitive.initial_radius, s.vertices[v]);
    if (!framing.valid) return kNoVertex;
    points.points.push_back(framing.point);
    points.input_vertex.push_back(v);
    return point_of[v] = static_cast<Index>(points.points.size() - 1);
  };
  Patch patch;
  for (Index f : selected) {
    const Tri t{add(s.faces[f][0]), add(s.faces[f][1]), add(s.faces[f][2])};
    if (t[0] == kNoVertex || t[1] == kNoVertex || t[2] == kNoVertex) continue;
    if (!consistent_triangle(points.points[t[0]], points.points[t[1]], points.points[t[2]])) continue;
    patch.faces.push_back(t);
    patch.input_face.push_back(f);
  }
  remove_pinches(patch);
  return patch;
}

Patch shrink_patch(const Patch& patch) {
  std::vector<Index> border;
  for (const auto& loop : border_loops(patch.faces).loops) border.insert(border.end(), loop.begin(), loop.end());
  std::sort(border.begin(), border.end());
  Patch shrunk = without_faces_at(patch, border);
  remove_pinches(shrunk);
  return shrunk;
}

}  // namespace medax::msd::refine
