#pragma once
// The mutable medial mesh that Q-MAT collapses: spheres in normalised units, vertex adjacency,
// faces with their incident-vertex lists, and the merge of one vertex into another (notes §1.6:
// edges and faces of both ends re-inserted without duplicates, faces holding both ends vanish).
#include "list_pool.hpp"
#include "slab_quadric.hpp"

#include <medax/medial_complex.hpp>

#include <vector>

namespace medax::qmat {

class CollapseMesh {
 public:
  /// The complex's spheres divided by `unit_length`; edges are its edges and every face side.
  CollapseMesh(const MedialComplex& medial, double unit_length);

  std::size_t size() const { return spheres.size(); }
  std::size_t live_vertices() const { return live_; }
  bool alive(Index v) const { return alive_[v] != 0; }
  bool face_alive(Index f) const { return face_alive_[f] != 0; }

  /// Neighbours of v (sorted, live); valid until the next merge.
  ListPool::View neighbours(Index v) const { return neighbours_[v]; }
  /// Calls visit(face) for each live face incident to v (no allocation: the hot loops use it).
  template <typename Visit>
  void for_each_face(Index v, Visit&& visit) const {
    for (Index f : vertex_faces_[v])
      if (face_alive_[f]) visit(f);
  }
  /// The face slots that held v, live or not (check face_alive); valid until the next merge.
  ListPool::View face_list(Index v) const { return vertex_faces_[v]; }
  bool has_faces(Index v) const;
  /// The number of live faces holding both i and j, and one of them in `some` when there is one.
  std::size_t face_count(Index i, Index j, Index* some = nullptr) const;
  /// Vertices adjacent to both i and j.
  std::vector<Index> common_neighbours(Index i, Index j) const;
  const Tri& face(Index f) const { return faces_[f]; }
  std::size_t face_slots() const { return faces_.size(); }
  /// The input face a face slot came from (degenerate and repeated input faces get no slot).
  Index source_face(Index f) const { return source_face_[f]; }
  /// Whether a live face has the corners a, b, c (in any order).
  bool has_face(Index a, Index b, Index c) const;

  /// Requests v's sphere and lists into the cache (a hint: v's edges are about to be costed).
  void prefetch(Index v) const {
    __builtin_prefetch(&spheres[v]);
    __builtin_prefetch(face_list(v).begin());
    __builtin_prefetch(neighbours(v).begin());
  }

  /// Merges `gone` into `keep` (which must be adjacent); the caller sets keep's sphere.
  void merge(Index keep, Index gone);

  std::vector<Vec4> spheres;  ///< (centre, radius) / unit_length

 private:
  void add_faces(const MedialComplex& medial);
  void add_adjacency(const MedialComplex& medial);
  void move_face(Index f, Index from, Index to);
  void move_neighbours(Index keep, Index gone);

  std::vector<char> alive_, face_alive_;
  ListPool neighbours_, vertex_faces_;  // per vertex, in one array each
  std::vector<Index> source_face_;
  std::vector<Tri> faces_;  // original orientation, with merged vertices renamed
  std::size_t live_ = 0;
};

}  // namespace medax::qmat
