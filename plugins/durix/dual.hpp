#pragma once
// The Delaunay / Voronoi duality between a Delaunay surface mesh and its interior medial axis
// (notes §2): the Delaunay tetrahedralization (DT) of the surface vertices, the current solid
// (a set of DT cells), and O(1) navigation over medial half-edges.
//
//   DT cell in the solid             -> medial node (circumcentre, circumradius)
//   DT facet between two solid cells -> medial edge, of degree = #volumetric edges of the facet
//   DT edge with every cell solid    -> medial face (a planar Voronoi polygon): "volumetric"
//
// A medial half-edge is (facet t, DT edge uv of t, corner u): one side of the medial face dual
// to uv, at the medial edge dual to t. Orientation rule (notes §2.3): with w the third vertex of
// t, the half-edge runs from the cell on the + side of (u, v, w) (orient3d(u, v, w, d) > 0 for
// its fourth vertex d) to the cell on the − side. DT cells are positively oriented, so "the +
// side" is a permutation parity: exact, no arithmetic.
//
// The solid changes when regions are carved away (notes §3.6); the DT never changes.
#include <medax/geometry.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace medax::durix {

using CellId = std::uint32_t;
using EdgeId = std::uint32_t;
constexpr std::uint32_t kNoId = std::numeric_limits<std::uint32_t>::max();

/// Local index pair (i < j) of a cell edge -> 0..5.
constexpr int kPairIndex[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};
constexpr int kPairVerts[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

/// A DT facet, named canonically by the smaller of its two cells and the local index of the
/// opposite vertex in that cell.
struct Facet {
  CellId cell = kNoId;
  std::uint8_t k = 0;
  bool operator==(const Facet& o) const { return cell == o.cell && k == o.k; }
  bool operator!=(const Facet& o) const { return !(*this == o); }
  bool operator<(const Facet& o) const { return cell != o.cell ? cell < o.cell : k < o.k; }
};

/// A medial half-edge: facet t, the face's DT edge (u, v) ⊂ t, corner u.
struct HalfEdge {
  Facet t;
  Index u = 0, v = 0;
  bool operator==(const HalfEdge& o) const { return t == o.t && u == o.u && v == o.v; }
  bool operator!=(const HalfEdge& o) const { return !(*this == o); }
  bool operator<(const HalfEdge& o) const {
    if (t != o.t) return t < o.t;
    return u != o.u ? u < o.u : v < o.v;
  }
};

struct HalfEdgeHash {
  std::size_t operator()(const HalfEdge& h) const {
    std::uint64_t x = (std::uint64_t(h.t.cell) << 2 | h.t.k) * 0x9E3779B97F4A7C15ull;
    x ^= (std::uint64_t(h.u) << 32 | h.v) + 0x7F4A7C159E3779B9ull + (x << 6) + (x >> 2);
    return static_cast<std::size_t>(x);
  }
};

class Dual {
 public:
  /// Builds the DT of `points` and the solid bounded by the outward-oriented Delaunay mesh
  /// `faces`. Throws std::invalid_argument naming the problem when a face is not a DT facet,
  /// when the faces do not bound a solid consistently, or when points repeat.
  Dual(const std::vector<Vec3>& points, const std::vector<Tri>& faces);

  // --- DT ----------------------------------------------------------------------------------
  std::size_t num_cells() const { return cells_.size(); }
  std::size_t num_points() const { return points_.size(); }
  const std::array<Index, 4>& cell(CellId c) const { return cells_[c]; }
  /// Neighbour across the facet opposite local k; kNoId for the infinite cell.
  CellId neighbour(CellId c, int k) const { return nbrs_[c][k]; }
  const Vec3& point(Index v) const { return points_[v]; }
  const Vec3& centre(CellId c) const { return centres_[c]; }
  double radius(CellId c) const { return radii_[c]; }
  /// A flat cell (four nearly cocircular corners): its ball is the circumcircle of its largest
  /// facet, not a true circumsphere.
  bool flat(CellId c) const { return flat_[c]; }
  int local(CellId c, Index v) const {
    const auto& q = cells_[c];
    return q[0] == v ? 0 : q[1] == v ? 1 : q[2] == v ? 2 : q[3] == v ? 3 : -1;
  }
  /// Cells incident to vertex v (every DT cell, solid or not, finite only).
  const CellId* vertex_cells_begin(Index v) const { return vcells_.data() + voffset_[v]; }
  const CellId* vertex_cells_end(Index v) const { return vcells_.data() + voffset_[v + 1]; }

  // --- solid -------------------------------------------------------------------------------
  bool solid(CellId c) const { return c != kNoId && solid_[c]; }
  /// Solid component id of the cell at construction (connected through non-surface facets).
  int component(CellId c) const { return component_[c]; }
  int num_components() const { return num_components_; }
  /// Sets cells in or out of the solid, keeping the edge counters in sync.
  void set_solid(CellId c, bool in);
  /// A vertex is on the current surface iff some solid cell uses it.
  bool on_surface(Index v) const { return solid_uses_[v] > 0; }
  bool original_vertex_used(Index v) const { return used_[v]; }

  // --- facets ------------------------------------------------------------------------------
  Facet facet(CellId c, int k) const;  ///< canonical name of the facet opposite local k of c
  CellId other_cell(const Facet& f) const { return nbrs_[f.cell][f.k]; }
  std::array<Index, 3> facet_vertices(const Facet& f) const;
  /// A facet between two solid cells: a medial edge.
  bool is_medial_edge(const Facet& f) const { return solid(f.cell) && solid(other_cell(f)); }
  /// A facet between a solid and a non-solid cell: a face of the current surface.
  bool is_surface_facet(const Facet& f) const { return solid(f.cell) != solid(other_cell(f)); }
  /// Number of volumetric DT edges of the facet (the number of medial faces around the edge).
  int degree(const Facet& f) const;
  bool forced(const Facet& f) const { return forced_[f.cell] >> f.k & 1; }
  void set_forced(const Facet& f, bool on);
  void clear_forced();

  // --- DT edges / medial faces --------------------------------------------------------------
  std::size_t num_edges() const { return edge_verts_.size(); }
  EdgeId cell_edge(CellId c, int pair) const { return cell_edges_[c][pair]; }
  EdgeId edge_of(CellId c, Index a, Index b) const { return cell_edges_[c][kPairIndex[local(c, a)][local(c, b)]]; }
  const std::array<Index, 2>& edge_vertices(EdgeId e) const { return edge_verts_[e]; }
  /// Every cell around the edge is solid: the dual Voronoi face is a medial face.
  bool volumetric(EdgeId e) const { return ring_size_[e] > 0 && solid_count_[e] == ring_size_[e]; }
  /// Some but not all cells around the edge are solid: an edge of the current surface.
  bool surface_edge(EdgeId e) const { return solid_count_[e] > 0 && !volumetric(e); }
  std::uint32_t solid_count_of(EdgeId e) const { return solid_count_[e]; }
  CellId edge_cell(EdgeId e) const { return edge_cell_[e]; }
  /// The cells around edge e in rotation order (the ring of its Voronoi face).
  void ring(EdgeId e, std::vector<CellId>& out) const;
  /// Calls f(facet) once for every facet between two solid cells: the medial edges of the solid.
  template <typename F>
  void for_each_solid_facet(const F& f) const {
    for (CellId c = 0; c < num_cells(); ++c) {
      if (!solid(c)) continue;
      for (int k = 0; k < 4; ++k) {
        const CellId n = neighbour(c, k);
        if (solid(n) && n > c) f(facet(c, k));
      }
    }
  }
  /// Calls f(half_edge) for both half-edges, u → v then v → u, of each volumetric side of facet t.
  template <typename F>
  void for_each_half_edge(const Facet& t, const F& f) const {
    const auto v = facet_vertices(t);
    for (int i = 0; i < 3; ++i) {
      const Index a = v[i], b = v[(i + 1) % 3];
      if (!volumetric(edge_of(t.cell, a, b))) continue;
      f(HalfEdge{t, a, b});
      f(HalfEdge{t, b, a});
    }
  }
  /// The facets around edge e, in the same order: out[i] between ring[i] and ring[i+1].
  void ring_facets(EdgeId e, std::vector<Facet>& out) const;
  int label(EdgeId e) const { return label_[e]; }
  void set_label(EdgeId e, int l) { label_[e] = l; }
  void clear_labels();
  /// Recounts the solid cells around every edge: the number of edges whose counter is wrong.
  std::size_t verify_counters() const;

  // --- half-edges ---------------------------------------------------------------------------
  Index third(const HalfEdge& h) const;
  EdgeId face(const HalfEdge& h) const;
  /// Start and end medial nodes.
  CellId start(const HalfEdge& h) const;
  CellId end(const HalfEdge& h) const;
  HalfEdge cell_nbr(const HalfEdge& h) const { return {h.t, h.u, third(h)}; }
  HalfEdge flip(const HalfEdge& h) const { return {h.t, h.v, h.u}; }
  /// The next half-edge on the same half-face (starts where h ends).
  HalfEdge next(const HalfEdge& h) const;
  HalfEdge prev(const HalfEdge& h) const;
  /// The neighbouring half-edge on the same side across the medial edge (reversed direction);
  /// skips open faces. Requires face(h) to be volumetric.
  HalfEdge side_nbr(const HalfEdge& h) const;

  /// Node type (notes §2.2): the number of components of the cell's 4 vertices joined by its
  /// surface edges (1 boundary, 2 regular, 3+ singular).
  int node_components(CellId c) const;

  /// Surface faces (outward oriented) of the current solid, by facet.
  std::vector<Facet> surface_facets() const;
  /// Outward-oriented vertex triple of a surface facet.
  Tri oriented_surface_triangle(const Facet& f) const;

 private:
  void build_edges();
  void circumsphere(CellId c);
  void classify(const std::vector<Tri>& faces);
  /// Per cell: which of its facets are input faces, and whether an input face sees it from
  /// outside; the cells an input face sees from inside seed the flood.
  struct SurfaceCells {
    std::vector<std::uint8_t> facet_mask;
    std::vector<char> exterior;
    std::vector<CellId> interior_seeds;  ///< sorted, unique
  };
  SurfaceCells mark_surface_facets(const std::vector<Tri>& faces);
  /// Solid cells: the flood from the seeds through facets that are no input face, one
  /// component per seed not yet reached.
  void flood_interior(const SurfaceCells& marks);
  void count_solid_uses();
  /// +1 when (a,b,c,d) is an even permutation of cell c's corners, -1 when odd.
  int parity(CellId c, Index a, Index b, Index cc, Index d) const;

  std::vector<Vec3> points_;
  std::vector<std::array<Index, 4>> cells_;
  std::vector<std::array<CellId, 4>> nbrs_;
  std::vector<Vec3> centres_;
  std::vector<double> radii_;
  std::vector<std::uint8_t> flat_;
  std::vector<std::uint32_t> voffset_;
  std::vector<CellId> vcells_;
  std::vector<std::uint8_t> solid_, forced_;
  std::vector<int> component_;
  int num_components_ = 0;
  std::vector<std::uint32_t> solid_uses_;
  std::vector<char> used_;

  std::vector<std::array<EdgeId, 6>> cell_edges_;
  std::vector<std::array<Index, 2>> edge_verts_;
  std::vector<CellId> edge_cell_;
  std::vector<std::uint32_t> ring_size_;  ///< 0 when the ring touches the infinite cell
  std::vector<std::uint32_t> solid_count_;
  std::vector<int> label_;
};

}  // namespace medax::durix
