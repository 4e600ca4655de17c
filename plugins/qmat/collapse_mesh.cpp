#include "collapse_mesh.hpp"

#include <medax/services/blocks.hpp>

#include <algorithm>
#include <iterator>

namespace medax::qmat {

namespace {

bool holds(const Tri& t, Index v) { return t[0] == v || t[1] == v || t[2] == v; }

void insert_sorted(std::vector<Index>& list, Index v) {
  auto it = std::lower_bound(list.begin(), list.end(), v);
  if (it == list.end() || *it != v) list.insert(it, v);
}

void erase_sorted(std::vector<Index>& list, Index v) {
  auto it = std::lower_bound(list.begin(), list.end(), v);
  if (it != list.end() && *it == v) list.erase(it);
}

/// Adds `per_corner` to count[v] for each element holding v.
template <typename Element>
void count_per_vertex(std::vector<std::size_t>& count, const std::vector<Element>& elements, std::size_t per_corner) {
  for (const Element& e : elements)
    for (Index v : e) count[v] += per_corner;
}

/// Room for count[v] entries in lists[v] (one allocation per list).
void reserve(std::vector<std::vector<Index>>& lists, const std::vector<std::size_t>& count) {
  for (std::size_t v = 0; v < lists.size(); ++v) lists[v].reserve(count[v]);
}

}  // namespace

CollapseMesh::CollapseMesh(const MedialComplex& medial, double unit_length)
    : alive_(medial.num_vertices(), 1), neighbours_(medial.num_vertices()), vertex_faces_(medial.num_vertices()),
      live_(medial.num_vertices()) {
  spheres.reserve(medial.num_vertices());
  for (std::size_t v = 0; v < medial.num_vertices(); ++v)
    spheres.push_back(sphere4(medial.centres[v] / unit_length, medial.radii[v] / unit_length));
  add_faces(medial);
  add_adjacency(medial);
}

/// One slot per input face, in input order, except degenerate faces and repeats of an earlier one.
void CollapseMesh::add_faces(const MedialComplex& medial) {
  std::vector<std::size_t> count(vertex_faces_.size(), 0);
  count_per_vertex(count, medial.faces, 1);
  reserve(vertex_faces_, count);
  for (Index input = 0; input < medial.faces.size(); ++input) {
    const Tri& t = medial.faces[input];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || has_face(t[0], t[1], t[2])) continue;
    const Index f = static_cast<Index>(faces_.size());
    faces_.push_back(t);
    source_face_.push_back(input);
    face_alive_.push_back(1);
    for (Index v : t) vertex_faces_[v].push_back(f);
  }
}

/// Neighbours: the complex's edges and every side of a face slot, sorted and without repeats
/// (each vertex's list on its own, in parallel).
void CollapseMesh::add_adjacency(const MedialComplex& medial) {
  std::vector<std::size_t> count(neighbours_.size(), 0);
  count_per_vertex(count, medial.edges, 1);
  count_per_vertex(count, faces_, 2);  // two face sides meet at each corner
  reserve(neighbours_, count);
  auto add = [&](Index a, Index b) {
    if (a == b) return;
    neighbours_[a].push_back(b);
    neighbours_[b].push_back(a);
  };
  for (const Segment& e : medial.edges) add(e[0], e[1]);
  for (const Tri& t : faces_)
    for (int k = 0; k < 3; ++k) add(t[k], t[(k + 1) % 3]);
  services::for_blocks(neighbours_.size(), 4096, true, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      std::vector<Index>& list = neighbours_[v];
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
  });
}

bool CollapseMesh::has_faces(Index v) const {
  for (Index f : vertex_faces_[v])
    if (face_alive_[f]) return true;
  return false;
}

std::size_t CollapseMesh::face_count(Index i, Index j, Index* some) const {
  const Index scan = vertex_faces_[i].size() <= vertex_faces_[j].size() ? i : j;
  const Index other = scan == i ? j : i;
  std::size_t count = 0;
  for (Index f : vertex_faces_[scan])
    if (face_alive_[f] && holds(faces_[f], other)) {
      if (some) *some = f;
      ++count;
    }
  return count;
}

std::vector<Index> CollapseMesh::common_neighbours(Index i, Index j) const {
  std::vector<Index> out;
  std::set_intersection(neighbours_[i].begin(), neighbours_[i].end(), neighbours_[j].begin(), neighbours_[j].end(),
                        std::back_inserter(out));
  return out;
}

bool CollapseMesh::has_face(Index a, Index b, Index c) const {
  if (a == b || b == c || a == c) return false;  // face slots have three distinct corners
  Index scan = a;
  for (Index v : {b, c})
    if (vertex_faces_[v].size() < vertex_faces_[scan].size()) scan = v;
  for (Index f : vertex_faces_[scan]) {
    const Tri& t = faces_[f];
    if (face_alive_[f] && holds(t, a) && holds(t, b) && holds(t, c)) return true;
  }
  return false;
}

void CollapseMesh::move_face(Index f, Index from, Index to) {
  Tri t = faces_[f];
  for (Index& v : t)
    if (v == from) v = to;
  if (has_face(t[0], t[1], t[2])) {  // the same triangle already exists at `to`
    face_alive_[f] = 0;
    return;
  }
  faces_[f] = t;
  vertex_faces_[to].push_back(f);
}

void CollapseMesh::move_neighbours(Index keep, Index gone) {
  for (Index n : neighbours_[gone]) {
    erase_sorted(neighbours_[n], gone);
    if (n == keep) continue;
    insert_sorted(neighbours_[n], keep);
    insert_sorted(neighbours_[keep], n);
  }
  neighbours_[gone].clear();
  neighbours_[gone].shrink_to_fit();
}

void CollapseMesh::merge(Index keep, Index gone) {
  for (Index f : vertex_faces_[gone]) {
    if (!face_alive_[f]) continue;
    if (holds(faces_[f], keep)) face_alive_[f] = 0;
    else move_face(f, gone, keep);
  }
  vertex_faces_[gone].clear();
  vertex_faces_[gone].shrink_to_fit();
  std::vector<Index>& kept = vertex_faces_[keep];
  kept.erase(std::remove_if(kept.begin(), kept.end(), [&](Index f) { return !face_alive_[f]; }), kept.end());
  move_neighbours(keep, gone);
  alive_[gone] = 0;
  --live_;
}

}  // namespace medax::qmat
