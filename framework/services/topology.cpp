#include <medax/services/topology.hpp>

#include <fmt/format.h>

#include <medax/union_find.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <stdexcept>

namespace medax::services {

namespace {

using Edge = std::array<Index, 2>;

/// Symmetric difference of two sorted index lists (addition over Z/2).
void add_mod2(std::vector<Index>& column, const std::vector<Index>& other, std::vector<Index>& scratch) {
  scratch.clear();
  std::set_symmetric_difference(column.begin(), column.end(), other.begin(), other.end(), std::back_inserter(scratch));
  column.swap(scratch);
}

/// Edge -> incident triangles, as compressed rows: the triangles of edge e are
/// incident[start[e], start[e + 1]).
struct Incidence {
  std::vector<std::size_t> start;
  std::vector<Index> incident;
};

Incidence edge_triangles(std::size_t num_edges, const std::vector<std::array<Index, 3>>& face_edges) {
  Incidence in;
  in.start.assign(num_edges + 1, 0);
  for (const auto& fe : face_edges)
    for (Index e : fe) ++in.start[e + 1];
  std::partial_sum(in.start.begin(), in.start.end(), in.start.begin());
  in.incident.resize(in.start.back());
  std::vector<std::size_t> fill(in.start.begin(), in.start.end() - 1);
  for (std::size_t f = 0; f < face_edges.size(); ++f)
    for (Index e : face_edges[f]) in.incident[fill[e]++] = static_cast<Index>(f);
  return in;
}

/// Free-face collapses: a triangle owning an edge alone is independent of all the others. Marks
/// the collapsed triangles dead in `alive` and returns their number (their share of the rank).
std::size_t collapse_free_faces(const std::vector<std::array<Index, 3>>& face_edges, const Incidence& in,
                                std::vector<char>& alive) {
  const std::size_t num_edges = in.start.size() - 1;
  std::vector<Index> count(num_edges);
  for (std::size_t e = 0; e < num_edges; ++e) count[e] = static_cast<Index>(in.start[e + 1] - in.start[e]);
  std::vector<Index> queue;
  for (std::size_t e = 0; e < num_edges; ++e)
    if (count[e] == 1) queue.push_back(static_cast<Index>(e));
  std::size_t rank = 0;
  while (!queue.empty()) {
    const Index e = queue.back();
    queue.pop_back();
    if (count[e] != 1) continue;
    Index f = 0;
    for (std::size_t k = in.start[e]; k < in.start[e + 1]; ++k)
      if (alive[in.incident[k]]) {
        f = in.incident[k];
        break;
      }
    alive[f] = 0;
    ++rank;
    for (Index other : face_edges[f])
      if (--count[other] == 1) queue.push_back(other);
  }
  return rank;
}

/// The live triangles in breadth-first order across shared edges.
std::vector<Index> breadth_first(const std::vector<std::array<Index, 3>>& face_edges, const Incidence& in,
                                 const std::vector<char>& alive) {
  const std::size_t nf = face_edges.size();
  std::vector<Index> order;
  std::vector<char> seen(nf, 0);
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (!alive[seed] || seen[seed]) continue;
    seen[seed] = 1;
    std::size_t head = order.size();
    order.push_back(static_cast<Index>(seed));
    while (head < order.size()) {
      const Index f = order[head++];
      for (Index e : face_edges[f])
        for (std::size_t k = in.start[e]; k < in.start[e + 1]; ++k) {
          const Index g = in.incident[k];
          if (alive[g] && !seen[g]) {
            seen[g] = 1;
            order.push_back(g);
          }
        }
    }
  }
  return order;
}

/// Rank over Z/2 of the boundary columns of the triangles `order`, reduced in that order with
/// edges ranked by first appearance and pivot = highest rank.
std::size_t reduced_rank(std::size_t num_edges, const std::vector<std::array<Index, 3>>& face_edges,
                         const std::vector<Index>& order) {
  constexpr Index kUnranked = Index(-1);
  std::vector<Index> edge_rank(num_edges, kUnranked);
  Index next_rank = 0;
  std::vector<std::int64_t> owner;
  std::vector<std::vector<Index>> reduced;
  std::vector<Index> column, scratch;
  std::size_t rank = 0;
  for (Index f : order) {
    column.clear();
    for (Index e : face_edges[f]) {
      if (edge_rank[e] == kUnranked) {
        edge_rank[e] = next_rank++;
        owner.push_back(-1);
      }
      column.push_back(edge_rank[e]);
    }
    std::sort(column.begin(), column.end());
    while (!column.empty() && owner[column.back()] >= 0)
      add_mod2(column, reduced[static_cast<std::size_t>(owner[column.back()])], scratch);
    if (column.empty()) continue;
    owner[column.back()] = static_cast<std::int64_t>(reduced.size());
    reduced.push_back(column);
    ++rank;
  }
  return rank;
}

/// rank of ∂2 over Z/2; `face_edges` holds the (sorted) edge indices of each triangle.
/// Free faces are collapsed first; the column reduction of what is left (the triangles of
/// possible 2-cycles: closed surfaces, books of pages...) takes the triangles in breadth-first
/// order across shared edges and ranks edges by first appearance in that order, with pivot =
/// highest rank: a triangle that brings a new edge gets it as its pivot at once, and only the
/// triangles closing a cycle need reducing. A closed surface then costs about F·√F, not F².
std::size_t boundary_rank(std::size_t num_edges, const std::vector<std::array<Index, 3>>& face_edges) {
  const Incidence in = edge_triangles(num_edges, face_edges);
  std::vector<char> alive(face_edges.size(), 1);
  const std::size_t collapsed = collapse_free_faces(face_edges, in, alive);
  return collapsed + reduced_rank(num_edges, face_edges, breadth_first(face_edges, in, alive));
}

}  // namespace

namespace {

/// The complex's distinct proper triangles and distinct edges (the listed ones and the triangles'
/// sides; a face with two equal corners counts as its edge), each sorted.
struct CellLists {
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Edge> edges;
};

CellLists distinct_cells(std::size_t num_vertices, const std::vector<Segment>& edges, const std::vector<Tri>& faces) {
  const auto check = [num_vertices](Index v, const char* kind, std::size_t i) {
    if (v >= num_vertices)
      throw std::invalid_argument(
          fmt::format("complex topology: {} {} refers to vertex {} of {}", kind, i, v, num_vertices));
  };
  CellLists c;
  c.triangles.reserve(faces.size());
  c.edges.reserve(edges.size() + 3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::array<Index, 3> k = faces[f];
    for (Index v : k) check(v, "face", f);
    std::sort(k.begin(), k.end());
    if (k[0] != k[1] && k[1] != k[2]) {
      c.triangles.push_back(k);
      c.edges.insert(c.edges.end(), {{k[0], k[1]}, {k[1], k[2]}, {k[0], k[2]}});
    } else if (k[0] != k[2]) {
      c.edges.push_back({k[0], k[2]});
    }
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Segment& s = edges[e];
    for (Index v : s) check(v, "edge", e);
    if (s[0] != s[1]) c.edges.push_back({std::min(s[0], s[1]), std::max(s[0], s[1])});
  }
  std::sort(c.triangles.begin(), c.triangles.end());
  c.triangles.erase(std::unique(c.triangles.begin(), c.triangles.end()), c.triangles.end());
  std::sort(c.edges.begin(), c.edges.end());
  c.edges.erase(std::unique(c.edges.begin(), c.edges.end()), c.edges.end());
  return c;
}

/// Each triangle's three edges, as sorted indices into the sorted edge list.
std::vector<std::array<Index, 3>> triangle_edges(const CellLists& c) {
  const auto edge_index = [&](Index a, Index b) {
    return static_cast<Index>(std::lower_bound(c.edges.begin(), c.edges.end(), Edge{a, b}) - c.edges.begin());
  };
  std::vector<std::array<Index, 3>> face_edges(c.triangles.size());
  for (std::size_t f = 0; f < c.triangles.size(); ++f) {
    const auto& k = c.triangles[f];
    face_edges[f] = {edge_index(k[0], k[1]), edge_index(k[1], k[2]), edge_index(k[0], k[2])};
    std::sort(face_edges[f].begin(), face_edges[f].end());
  }
  return face_edges;
}

}  // namespace

ComplexTopology complex_topology(std::size_t num_vertices, const std::vector<Segment>& edges,
                                 const std::vector<Tri>& faces) {
  const CellLists cells = distinct_cells(num_vertices, edges, faces);
  ComplexTopology t;
  t.vertices = num_vertices;
  t.edges = cells.edges.size();
  t.faces = cells.triangles.size();
  t.euler = static_cast<long long>(t.vertices) - static_cast<long long>(t.edges) + static_cast<long long>(t.faces);

  UnionFind components(num_vertices);
  for (const Edge& e : cells.edges) components.unite(e[0], e[1]);
  t.b0 = components.count();
  // Over Z/2: b1 = E − rank ∂1 − rank ∂2, b2 = F − rank ∂2, with rank ∂1 = V − b0.
  const std::size_t rank2 = boundary_rank(cells.edges.size(), triangle_edges(cells));
  const std::size_t rank1 = t.vertices - t.b0;
  t.b2 = t.faces - rank2;
  t.b1 = t.edges - rank1 - rank2;
  return t;
}

ComplexTopology complex_topology(const MedialComplex& medial) {
  return complex_topology(medial.num_vertices(), medial.edges, medial.faces);
}

double SurfaceTopology::genus() const {
  if (!closed()) return -1;
  return static_cast<double>(complex.b0) - 0.5 * static_cast<double>(complex.euler);
}

SurfaceTopology surface_topology(const SurfaceMesh& mesh) {
  // Only the vertices some face uses.
  std::vector<Index> remap(mesh.vertices.size(), Index(-1));
  Index used = 0;
  std::vector<Tri> faces(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.faces[f][k];
      if (v >= mesh.vertices.size())
        throw std::invalid_argument(fmt::format("surface topology: face {} refers to vertex {} of {}", f, v,
                                                mesh.vertices.size()));
      if (remap[v] == Index(-1)) remap[v] = used++;
      faces[f][k] = remap[v];
    }
  SurfaceTopology s;
  s.complex = complex_topology(used, {}, faces);
  // Faces per edge (each distinct triangle once).
  std::vector<std::array<Index, 3>> tris;
  for (const Tri& f : faces) {
    std::array<Index, 3> k = f;
    std::sort(k.begin(), k.end());
    if (k[0] != k[1] && k[1] != k[2]) tris.push_back(k);
  }
  std::sort(tris.begin(), tris.end());
  tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
  std::vector<Edge> sides;
  for (const auto& k : tris) sides.insert(sides.end(), {{k[0], k[1]}, {k[1], k[2]}, {k[0], k[2]}});
  std::sort(sides.begin(), sides.end());
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    if (j - i == 1) ++s.boundary_edges;
    if (j - i >= 3) ++s.nonmanifold_edges;
    i = j;
  }
  return s;
}

}  // namespace medax::services
