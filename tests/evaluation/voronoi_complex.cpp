#include "voronoi_complex.hpp"

#include <medax/services/delaunay.hpp>
#include <medax/services/inside.hpp>

#include <algorithm>
#include <array>
#include <cstdint>

namespace medax::bench {

MedialComplex interior_voronoi_complex(const SurfaceMesh& mesh) {
  using services::DelaunayTetrahedralization;
  const DelaunayTetrahedralization dt = services::delaunay_tetrahedralize(mesh.vertices);
  const services::InsideTest inside(mesh);
  const std::vector<char> interior = inside.inside(dt.circumcentres);

  MedialComplex mc;
  std::vector<std::int64_t> vertex_of(dt.cells.size(), -1);
  for (std::size_t c = 0; c < dt.cells.size(); ++c)
    if (interior[c]) vertex_of[c] = mc.add_vertex(dt.circumcentres[c], dt.circumradii[c]);

  // Voronoi edges: facets between two interior cells.
  for (std::size_t c = 0; c < dt.cells.size(); ++c)
    for (int k = 0; k < 4; ++k) {
      const std::int64_t n = dt.neighbours[c][k];
      if (n > static_cast<std::int64_t>(c) && vertex_of[c] >= 0 && vertex_of[n] >= 0)
        mc.add_edge(static_cast<Index>(vertex_of[c]), static_cast<Index>(vertex_of[n]));
    }

  // Voronoi faces: group the cells by Delaunay edge, then walk each ring in cyclic order.
  struct Entry {
    std::uint64_t edge;
    Index cell;
  };
  std::vector<Entry> entries;
  entries.reserve(6 * dt.cells.size());
  for (std::size_t c = 0; c < dt.cells.size(); ++c) {
    if (vertex_of[c] < 0) continue;  // a ring with an exterior cell is dropped anyway
    const auto& v = dt.cells[c];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const std::uint64_t a = std::min(v[i], v[j]), b = std::max(v[i], v[j]);
        entries.push_back({(a << 32) | b, static_cast<Index>(c)});
      }
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& x, const Entry& y) { return x.edge < y.edge || (x.edge == y.edge && x.cell < y.cell); });
  std::vector<Index> ring;
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i;
    while (j < entries.size() && entries[j].edge == entries[i].edge) ++j;
    const Index a = static_cast<Index>(entries[i].edge >> 32), b = static_cast<Index>(entries[i].edge & 0xffffffffu);
    const std::size_t group = j - i;
    // Walk around the edge from the first cell.
    ring.clear();
    bool closed = false;
    std::int64_t prev = -1, cur = entries[i].cell;
    for (std::size_t step = 0; step <= group + 1; ++step) {
      if (cur < 0 || vertex_of[cur] < 0) break;  // infinite or exterior cell
      ring.push_back(static_cast<Index>(cur));
      const auto& v = dt.cells[cur];
      std::array<std::int64_t, 2> next{};
      int m = 0;
      for (int k = 0; k < 4; ++k)
        if (v[k] != a && v[k] != b) next[m++] = dt.neighbours[cur][k];
      const std::int64_t n = next[0] != prev ? next[0] : next[1];
      prev = cur;
      cur = n;
      if (cur == entries[i].cell) {
        closed = true;
        break;
      }
    }
    if (closed && ring.size() == group && group >= 3)
      for (std::size_t k = 1; k + 1 < ring.size(); ++k)
        mc.add_face(static_cast<Index>(vertex_of[ring[0]]), static_cast<Index>(vertex_of[ring[k]]),
                    static_cast<Index>(vertex_of[ring[k + 1]]));
    i = j;
  }
  return mc;
}

}  // namespace medax::bench
