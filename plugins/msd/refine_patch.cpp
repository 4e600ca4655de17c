#include "refine_patch.hpp"

#include "refine_topology.hpp"

#include <algorithm>
#include <deque>
#include <map>
#include <set>
#include <unordered_map>

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

/// S's faces by directed halfedge (a, b) → the face holding it.
std::unordered_map<std::uint64_t, Index> faces_by_halfedge(const SurfaceMesh& s) {
  std::unordered_map<std::uint64_t, Index> map;
  map.reserve(3 * s.faces.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      map.emplace((std::uint64_t{s.faces[f][k]} << 32) | s.faces[f][(k + 1) % 3], static_cast<Index>(f));
  return map;
}

/// The S faces beyond one patch border loop (in S ids), found by a flood fill that stops at
/// patch faces; empty when more than `limit` are reached (the loop is not a small hole).
std::vector<Index> hole_faces(const SurfaceMesh& s, const std::unordered_map<std::uint64_t, Index>& by_halfedge,
                              const std::vector<Index>& loop, const std::vector<char>& in_patch, std::size_t limit) {
  std::vector<Index> found;
  std::set<Index> seen;
  std::deque<Index> queue;
  const auto visit = [&](Index a, Index b) {  // the face across S's halfedge a → b
    const auto it = by_halfedge.find((std::uint64_t{b} << 32) | a);
    if (it == by_halfedge.end() || in_patch[it->second] || !seen.insert(it->second).second) return;
    queue.push_back(it->second);
  };
  for (std::size_t i = 0; i < loop.size(); ++i) visit(loop[i], loop[(i + 1) % loop.size()]);
  while (!queue.empty() && found.size() <= limit) {
    const Index f = queue.front();
    queue.pop_front();
    found.push_back(f);
    for (int k = 0; k < 3; ++k) visit(s.faces[f][(k + 1) % 3], s.faces[f][k]);
  }
  if (found.size() > limit || !queue.empty()) return {};
  std::sort(found.begin(), found.end());
  return found;
}

/// Small holes of the patch (at most `limit` S faces behind a border loop, e.g. one vertex the
/// selection missed) are filled with S's faces there when they are all consistent: the template
/// would otherwise keep a tiny island inside the patch that no band can join.
template <typename Take>
void fill_small_holes(const SurfaceMesh& s, std::size_t limit, std::vector<char>& in_patch, Patch& patch,
                      Take&& take) {
  if (limit == 0 || patch.faces.empty()) return;
  const auto by_halfedge = faces_by_halfedge(s);
  // Border loops in S ids.
  std::vector<Tri> s_faces;
  for (Index f : patch.input_face) s_faces.push_back(s.faces[f]);
  for (const auto& loop : border_loops(s_faces).loops) {
    const std::vector<Index> hole = hole_faces(s, by_halfedge, loop, in_patch, limit);
    const std::size_t before = patch.faces.size();
    bool all = !hole.empty();
    for (Index f : hole) all = all && !in_patch[f] && take(f);
    if (!all) {  // a hole that cannot be filled whole stays open
      for (std::size_t k = before; k < patch.faces.size(); ++k) in_patch[patch.input_face[k]] = 0;
      patch.faces.resize(before);
      patch.input_face.resize(before);
    }
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
                  std::size_t hole_limit, PointSet& points) {
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
  std::vector<char> in_patch(s.faces.size(), 0);
  const auto take = [&](Index f) {  // S face f joins the patch when it is consistent
    const Tri t{add(s.faces[f][0]), add(s.faces[f][1]), add(s.faces[f][2])};
    if (t[0] == kNoVertex || t[1] == kNoVertex || t[2] == kNoVertex) return false;
    if (!consistent_triangle(points.points[t[0]], points.points[t[1]], points.points[t[2]])) return false;
    patch.faces.push_back(t);
    patch.input_face.push_back(f);
    in_patch[f] = 1;
    return true;
  };
  for (Index f : selected) take(f);
  fill_small_holes(s, hole_limit, in_patch, patch, take);
  remove_pinches(patch);
  return patch;
}

Patch shrink_patch_at(const Patch& patch, std::vector<Index> loop) {
  std::sort(loop.begin(), loop.end());
  Patch shrunk = without_faces_at(patch, loop);
  remove_pinches(shrunk);
  return shrunk;
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
