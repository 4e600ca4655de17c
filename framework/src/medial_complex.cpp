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
  return static_cast<Index>(centres.size() - 1);
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

std::size_t MedialComplex::close_edges() {
  std::vector<Segment> all;
  all.reserve(edges.size() + 3 * faces.size());
  auto sorted = [](Index a, Index b) { return a < b ? Segment{a, b} : Segment{b, a}; };
  for (const Segment& e : edges) all.push_back(sorted(e[0], e[1]));
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) all.push_back(sorted(f[k], f[(k + 1) % 3]));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  const std::size_t before = edges.size();
  if (all != edges) {
    edges = std::move(all);
    edge_props = {};
  }
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
}

}  // namespace medax
