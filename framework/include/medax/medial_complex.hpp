#pragma once
// The medial complex: medial spheres (centre, radius) joined by edges and triangles. It may be
// non-manifold (an edge can bound three or more triangles), so it is a plain indexed structure;
// adjacency is built on demand by the algorithms that need it.
#include <medax/geometry.hpp>
#include <medax/properties.hpp>

#include <string>
#include <vector>

namespace medax {

enum class Element { Vertex, Edge, Face };

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

  Index add_vertex(const Vec3& centre, double radius);
  void add_edge(Index a, Index b) { edges.push_back({a, b}); }
  void add_face(Index a, Index b, Index c) { faces.push_back({a, b, c}); }

  ElementProperties& props(Element e);
  const ElementProperties& props(Element e) const;

  /// Adds every face edge that is missing from `edges`, and sorts/dedups edges (each stored as
  /// i < j). Edge properties are dropped when edges change, since their rows would no longer
  /// match. Returns the number of edges added.
  std::size_t close_edges();

  /// Throws std::runtime_error describing the first inconsistency: index out of range,
  /// a property column of the wrong length, non-finite centre, negative radius.
  void validate() const;

  /// Applies a similarity to every centre and radius.
  void transform(const Similarity& s);
};

}  // namespace medax
