#include "collapse_mesh.hpp"

#include <medax/services/blocks.hpp>

#include <algorithm>
#include <iterator>

namespace medax::qmat {

namespace {

bool holds(const Tri& t, Index v) { return t[0] == v || t[1] == v || t[2] == v; }

/// Adds `per_corner` to count[v] for each element holding v.
template <typename Element>
void count_per_vertex(std::vector<std::size_t>& count, const std::vector<Element>& elements, std::size_t per_corner) {
  for (const Element& e : elements)
    for (Index v : e) count[v] += per_corner;
}

}  // namespace

CollapseMesh::CollapseMesh(const MedialComplex& medial, double unit_length)
    : alive_(medial.num_vertices(), 1), live_(medial.num_vertices()) {
  spheres.reserve(medial.num_vertices());
  for (std::size_t v = 0; v < medial.num_vertices(); ++v)
    spheres.push_back(sphere4(medial.centres[v] / unit_length, medial.radii[v] / unit_length));
  add_faces(medial);
  add_adjacency(medial);
}

/// One slot per input face, in input order, except degenerate faces and repeats of an earlier one.
void CollapseMesh::add_faces(const MedialComplex& medial) {
  std::vector<std::size_t> count(medial.num_vertices(), 0);
  count_per_vertex(count, medial.faces, 1);
  vertex_faces_ = ListPool(count);
  for (Index input = 0; input < medial.faces.size(); ++input) {
    const Tri& t = medial.faces[input];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || has_face(t[0], t[1], t[2])) continue;
    const Index f = static_cast<Index>(faces_.size());
    faces_.push_back(t);
    source_face_.push_back(input);
    face_alive_.push_back(1);
    for (Index v : t) vertex_faces_.push_back(v, f);
  }
}

/// Neighbours: the complex's edges and every side of a face slot, sorted and without repeats
/// (each vertex's list on its own, in parallel).
void CollapseMesh::add_adjacency(const MedialComplex& medial) {
  std::vector<std::size_t> count(medial.num_vertices(), 0);
  count_per_vertex(count, medial.edges, 1);
  count_per_vertex(count, faces_, 2);  // two face sides meet at each corner
  neighbours_ = ListPool(count);
  auto add = [&](Index a, Index b) {
    if (a == b) return;
    neighbours_.push_back(a, b);
    neighbours_.push_back(b, a);
  };
  for (const Segment& e : medial.edges) add(e[0], e[1]);
  for (const Tri& t : faces_)
    for (int k = 0; k < 3; ++k) add(t[k], t[(k + 1) % 3]);
  services::for_blocks(medial.num_vertices(), 4096, true, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) neighbours_.sort_unique(v);
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
  const ListPool::View a = neighbours_[i], b = neighbours_[j];
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
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
  vertex_faces_.push_back(to, f);
}

/// (The lists grow as gone's is walked: it is read by position.)
void CollapseMesh::move_neighbours(Index keep, Index gone) {
  for (std::size_t k = 0; k < neighbours_[gone].size(); ++k) {
    const Index n = neighbours_[gone][k];
    neighbours_.erase_sorted(n, gone);
    if (n == keep) continue;
    neighbours_.insert_sorted(n, keep);
    neighbours_.insert_sorted(keep, n);
  }
  neighbours_.clear(gone);
}

void CollapseMesh::merge(Index keep, Index gone) {
  for (std::size_t k = 0; k < vertex_faces_[gone].size(); ++k) {  // by position: keep's list grows
    const Index f = vertex_faces_[gone][k];
    if (!face_alive_[f]) continue;
    if (holds(faces_[f], keep)) face_alive_[f] = 0;
    else move_face(f, gone, keep);
  }
  vertex_faces_.clear(gone);
  vertex_faces_.erase_if(keep, [&](Index f) { return !face_alive_[f]; });
  move_neighbours(keep, gone);
  alive_[gone] = 0;
  --live_;
}

}  // namespace medax::qmat
