#pragma once
// The medial complex: medial spheres (centre, radius) joined by edges and triangles. It may be
// non-manifold (an edge can bound three or more triangles), so it is a plain indexed structure;
// adjacency is built on demand by the algorithms that need it.
//
// The element vectors are open for reading and in-place edits; grow the complex with add_*()
// and shrink it with subcomplex(), which keep every property column and the generators in step.
#include <medax/geometry.hpp>
#include <medax/properties.hpp>

#include <string>
#include <vector>

namespace medax {

struct MedialComplex {
  std::vector<Vec3> centres;
  std::vector<double> radii;
  std::vector<Segment> edges;
  std::vector<Tri> faces;

  ElementProperties vertex_props, edge_props, face_props;

  /// Optional correspondence: for each medial vertex, the indices of the surface elements
  /// (mesh vertices or samples, as `generator_kind` says) that generate it. Empty when unknown.
  std::vector<std::vector<Index>> generators;
  std::string generator_kind;  ///< "mesh_vertex", "sample", ... ; empty when no correspondence

  std::size_t num_vertices() const { return centres.size(); }
  std::size_t size(Element e) const;

  /// Each adds one element and one row to every column of its kind (set to the column's
  /// initial value); add_vertex adds an empty generator list when there is a correspondence.
  Index add_vertex(const Vec3& centre, double radius);
  Index add_edge(Index a, Index b);
  Index add_face(Index a, Index b, Index c);

  ElementProperties& props(Element e);
  const ElementProperties& props(Element e) const;

  /// Adds a column for `p`, every row set to `init`, and returns it (replaces one of that name).
  template <typename T>
  std::vector<T>& add(const Property<T>& p, T init = T{}) {
    return props(p.element).template map<T>().add(p.name, size(p.element), init, p.length_power);
  }
  template <typename T>
  bool has(const Property<T>& p) const {
    return props(p.element).template map<T>().has(p.name);
  }
  /// The column of `p`; throws std::out_of_range naming it when there is none.
  template <typename T>
  const std::vector<T>& get(const Property<T>& p) const {
    return props(p.element).template map<T>().get(p.name);
  }
  template <typename T>
  std::vector<T>& get(const Property<T>& p) {
    return props(p.element).template map<T>().get(p.name);
  }

  /// The complex made of the listed vertices, edges and faces (indices into this complex, kept
  /// in the order given), vertices renumbered. Every property column and the generators follow
  /// their elements. Throws std::invalid_argument when a kept edge or face uses a vertex that
  /// is not kept.
  MedialComplex subcomplex(const std::vector<Index>& vertices, const std::vector<Index>& edges,
                           const std::vector<Index>& faces) const;

  /// Adds every face edge that is missing from `edges`, and sorts/dedups edges (each stored as
  /// i < j). Columns of edges that were there follow them; added edges get each column's
  /// initial value (of duplicate edges, the first keeps its row). Returns the number added.
  std::size_t close_edges();

  /// Throws std::runtime_error describing the first inconsistency: index out of range,
  /// a property column of the wrong length, non-finite centre, negative radius.
  void validate() const;

  /// Applies a similarity to every centre and radius, and to every field that scales with length
  /// (a field scaling as length^k is multiplied by s.scale^k; see Property::length_power).
  void transform(const Similarity& s);
};

}  // namespace medax
