#include "counts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace medax::evaluation {

Metrics ElementCounts::metrics() const {
  return {{"vertices", static_cast<double>(vertices)},
          {"edges", static_cast<double>(edges)},
          {"unique_edges", static_cast<double>(unique_edges)},
          {"faces", static_cast<double>(faces)},
          {"isolated_vertices", static_cast<double>(isolated_vertices)},
          {"N_d", static_cast<double>(discrete())},
          {"N_c", static_cast<double>(continuous())}};
}

ElementCounts count_elements(const MedialComplex& medial) {
  using Edge = std::array<Index, 2>;
  const std::size_t nv = medial.num_vertices();
  std::vector<std::array<Index, 3>> tris;
  std::vector<Edge> listed, sides;
  std::vector<char> used(nv, 0);
  const auto use = [&](Index v, const char* kind, std::size_t i) {
    if (v >= nv)
      throw std::invalid_argument(fmt::format("{} {} refers to vertex {} of {}", kind, i, v, nv));
    used[v] = 1;
  };
  for (std::size_t f = 0; f < medial.faces.size(); ++f) {
    std::array<Index, 3> k = medial.faces[f];
    for (Index v : k) use(v, "face", f);
    std::sort(k.begin(), k.end());
    if (k[0] != k[1] && k[1] != k[2]) {
      tris.push_back(k);
    } else if (k[0] != k[2]) {
      listed.push_back({k[0], k[2]});
    }
  }
  for (std::size_t e = 0; e < medial.edges.size(); ++e) {
    const Segment& s = medial.edges[e];
    for (Index v : s) use(v, "edge", e);
    if (s[0] != s[1]) listed.push_back({std::min(s[0], s[1]), std::max(s[0], s[1])});
  }
  std::sort(tris.begin(), tris.end());
  tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
  for (const auto& k : tris) sides.insert(sides.end(), {{k[0], k[1]}, {k[1], k[2]}, {k[0], k[2]}});
  std::sort(sides.begin(), sides.end());
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
  std::sort(listed.begin(), listed.end());
  listed.erase(std::unique(listed.begin(), listed.end()), listed.end());

  ElementCounts c;
  c.vertices = nv;
  c.faces = tris.size();
  for (const Edge& e : listed)
    if (!std::binary_search(sides.begin(), sides.end(), e)) ++c.unique_edges;
  c.edges = sides.size() + c.unique_edges;
  c.isolated_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), 0));
  return c;
}

}  // namespace medax::evaluation
