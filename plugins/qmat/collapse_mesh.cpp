#include "collapse_mesh.hpp"

#include <algorithm>

namespace medax::qmat {

namespace {

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

void insert_sorted(std::vector<Index>& list, Index v) {
  auto it = std::lower_bound(list.begin(), list.end(), v);
  if (it == list.end() || *it != v) list.insert(it, v);
}

void erase_sorted(std::vector<Index>& list, Index v) {
  auto it = std::lower_bound(list.begin(), list.end(), v);
  if (it != list.end() && *it == v) list.erase(it);
}

}  // namespace

std::size_t CollapseMesh::TriHash::operator()(const Tri& t) const {
  std::size_t h = t[0];
  h = h * 0x9E3779B97F4A7C15ull + t[1];
  return h * 0x9E3779B97F4A7C15ull + t[2];
}

CollapseMesh::CollapseMesh(const MedialComplex& medial, double unit_length)
    : alive_(medial.num_vertices(), 1), neighbours_(medial.num_vertices()), vertex_faces_(medial.num_vertices()),
      live_(medial.num_vertices()) {
  spheres.reserve(medial.num_vertices());
  for (std::size_t v = 0; v < medial.num_vertices(); ++v)
    spheres.push_back(sphere4(medial.centres[v] / unit_length, medial.radii[v] / unit_length));
  for (const Segment& e : medial.edges) add_edge(e[0], e[1]);
  face_index_.reserve(2 * medial.faces.size());
  for (Index input = 0; input < medial.faces.size(); ++input) {
    const Tri& t = medial.faces[input];
    const Tri key = sorted(t);
    if (key[0] == key[1] || key[1] == key[2] || face_index_.count(key)) continue;  // degenerate or repeated
    const Index f = static_cast<Index>(faces_.size());
    faces_.push_back(t);
    source_face_.push_back(input);
    face_alive_.push_back(1);
    face_index_.emplace(key, f);
    for (int k = 0; k < 3; ++k) {
      vertex_faces_[t[k]].push_back(f);
      add_edge(t[k], t[(k + 1) % 3]);
    }
  }
}

void CollapseMesh::add_edge(Index a, Index b) {
  if (a == b) return;
  insert_sorted(neighbours_[a], b);
  insert_sorted(neighbours_[b], a);
}

bool CollapseMesh::has_faces(Index v) const {
  for (Index f : vertex_faces_[v])
    if (face_alive_[f]) return true;
  return false;
}

std::size_t CollapseMesh::face_count(Index i, Index j) const {
  const Index scan = vertex_faces_[i].size() <= vertex_faces_[j].size() ? i : j;
  const Index other = scan == i ? j : i;
  std::size_t count = 0;
  for (Index f : vertex_faces_[scan]) {
    const Tri& t = faces_[f];
    count += face_alive_[f] && (t[0] == other || t[1] == other || t[2] == other);
  }
  return count;
}

std::vector<Index> CollapseMesh::faces_of_edge(Index i, Index j) const {
  const Index scan = vertex_faces_[i].size() <= vertex_faces_[j].size() ? i : j;
  const Index other = scan == i ? j : i;
  std::vector<Index> out;
  for (Index f : vertex_faces_[scan]) {
    const Tri& t = faces_[f];
    if (face_alive_[f] && (t[0] == other || t[1] == other || t[2] == other)) out.push_back(f);
  }
  return out;
}

std::vector<Index> CollapseMesh::common_neighbours(Index i, Index j) const {
  std::vector<Index> out;
  std::set_intersection(neighbours_[i].begin(), neighbours_[i].end(), neighbours_[j].begin(), neighbours_[j].end(),
                        std::back_inserter(out));
  return out;
}

bool CollapseMesh::has_face(Index a, Index b, Index c) const { return face_index_.count(sorted({a, b, c})) != 0; }

void CollapseMesh::kill_face(Index f) {
  face_alive_[f] = 0;
  face_index_.erase(sorted(faces_[f]));
}

void CollapseMesh::move_face(Index f, Index from, Index to) {
  Tri t = faces_[f];
  for (Index& v : t)
    if (v == from) v = to;
  face_index_.erase(sorted(faces_[f]));
  if (face_index_.count(sorted(t))) {  // the same triangle already exists at `to`
    face_alive_[f] = 0;
    return;
  }
  faces_[f] = t;
  face_index_.emplace(sorted(t), f);
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
    const Tri& t = faces_[f];
    if (t[0] == keep || t[1] == keep || t[2] == keep) kill_face(f);
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
