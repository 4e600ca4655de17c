#include <medax/medial_complex.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace medax {

std::size_t MedialComplex::size(Element e) const {
  switch (e) {
    case Element::Vertex: return centres.size();
    case Element::Edge: return edges.size();
    case Element::Face: return faces.size();
  }
  return 0;
}

Index MedialComplex::add_vertex(const Vec3& centre, double radius) {
  centres.push_back(centre);
  radii.push_back(radius);
  vertex_props.grow();
  if (!generators.empty() || !generator_kind.empty()) generators.resize(centres.size());
  return static_cast<Index>(centres.size() - 1);
}

Index MedialComplex::add_edge(Index a, Index b) {
  edges.push_back({a, b});
  edge_props.grow();
  return static_cast<Index>(edges.size() - 1);
}

Index MedialComplex::add_face(Index a, Index b, Index c) {
  faces.push_back({a, b, c});
  face_props.grow();
  return static_cast<Index>(faces.size() - 1);
}

ElementProperties& MedialComplex::props(Element e) {
  return const_cast<ElementProperties&>(static_cast<const MedialComplex&>(*this).props(e));
}
const ElementProperties& MedialComplex::props(Element e) const {
  switch (e) {
    case Element::Vertex: return vertex_props;
    case Element::Edge: return edge_props;
    case Element::Face: return face_props;
  }
  throw std::logic_error("unknown element kind");
}

MedialComplex MedialComplex::subcomplex(const std::vector<Index>& vertices, const std::vector<Index>& edge_rows,
                                        const std::vector<Index>& face_rows) const {
  constexpr Index kDropped = static_cast<Index>(-1);
  std::vector<Index> renumber(num_vertices(), kDropped);
  for (std::size_t k = 0; k < vertices.size(); ++k) renumber[vertices[k]] = static_cast<Index>(k);
  auto vertex = [&](Index v) {
    if (renumber[v] == kDropped)
      throw std::invalid_argument(fmt::format("subcomplex: vertex {} is used but not kept", v));
    return renumber[v];
  };
  MedialComplex out;
  out.generator_kind = generator_kind;
  for (Index v : vertices) {
    out.centres.push_back(centres[v]);
    out.radii.push_back(radii[v]);
    if (!generators.empty()) out.generators.push_back(generators[v]);
  }
  for (Index e : edge_rows) out.edges.push_back({vertex(edges[e][0]), vertex(edges[e][1])});
  for (Index f : face_rows) out.faces.push_back({vertex(faces[f][0]), vertex(faces[f][1]), vertex(faces[f][2])});
  out.vertex_props = vertex_props;
  out.vertex_props.select(vertices);
  out.edge_props = edge_props;
  out.edge_props.select(edge_rows);
  out.face_props = face_props;
  out.face_props.select(face_rows);
  return out;
}

std::size_t MedialComplex::close_edges() {
  // Every edge as (i < j) with the row it came from; face sides come as fresh rows and sort
  // after an existing row of the same edge, so unique() keeps the existing one.
  std::vector<std::pair<Segment, Index>> all;
  all.reserve(edges.size() + 3 * faces.size());
  auto sorted = [](Index a, Index b) { return a < b ? Segment{a, b} : Segment{b, a}; };
  for (Index e = 0; e < edges.size(); ++e) all.push_back({sorted(edges[e][0], edges[e][1]), e});
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) all.push_back({sorted(f[k], f[(k + 1) % 3]), kFreshRow});
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
            all.end());
  const std::size_t before = edges.size();
  std::vector<Segment> next;
  std::vector<Index> rows;
  for (const auto& [edge, row] : all) {
    next.push_back(edge);
    rows.push_back(row);
  }
  if (next == edges) return 0;
  edges = std::move(next);
  edge_props.select(rows);
  return edges.size() > before ? edges.size() - before : 0;
}

namespace {
template <typename T>
void check_columns(const PropertyMap<T>& map, std::size_t n, const char* kind) {
  for (const auto& [name, column] : map.all())
    if (column.size() != n)
      throw std::runtime_error(fmt::format("{} property '{}' has {} values for {} elements", kind,
                                           name, column.size(), n));
}
}  // namespace

void MedialComplex::validate() const {
  const std::size_t n = centres.size();
  if (radii.size() != n)
    throw std::runtime_error(fmt::format("{} centres but {} radii", n, radii.size()));
  for (std::size_t i = 0; i < n; ++i) {
    if (!centres[i].allFinite())
      throw std::runtime_error(fmt::format("vertex {} has a non-finite centre", i));
    if (!(radii[i] >= 0.0) || !std::isfinite(radii[i]))
      throw std::runtime_error(fmt::format("vertex {} has invalid radius {}", i, radii[i]));
  }
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (Index v : edges[i])
      if (v >= n) throw std::runtime_error(fmt::format("edge {} refers to vertex {} of {}", i, v, n));
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (Index v : faces[i])
      if (v >= n) throw std::runtime_error(fmt::format("face {} refers to vertex {} of {}", i, v, n));
  for (Element e : {Element::Vertex, Element::Edge, Element::Face}) {
    check_columns(props(e).fields, size(e), "field");
    check_columns(props(e).labels, size(e), "label");
  }
  if (!generators.empty() && generators.size() != n)
    throw std::runtime_error(fmt::format("{} generator lists for {} vertices", generators.size(), n));
}

void MedialComplex::transform(const Similarity& s) {
  for (Vec3& c : centres) c = s.apply(c);
  for (double& r : radii) r = s.apply_length(r);
  for (ElementProperties* props : {&vertex_props, &edge_props, &face_props})
    for (auto& [name, column] : props->fields.all()) {
      const int k = props->fields.length_power(name);
      if (k == 0) continue;
      const double factor = std::pow(s.scale, k);
      for (double& value : column) value *= factor;
    }
}

}  // namespace medax
