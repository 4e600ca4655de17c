// MEDIAL passes D–E (Dey & Zhao 2004): the angle and ratio conditions on every Delaunay edge,
// and the ring of cells (the dual Voronoi facet) of each selected edge.
#include "medial_passes.hpp"

#include <medax/services/blocks.hpp>
#include <medax/services/delaunay_rings.hpp>

#include <algorithm>
#include <cmath>

namespace medax::dey_zhao {

using services::DelaunayTetrahedralization;

EdgeScores score_edge(const std::vector<Vec3>& P, const Umbrellas& u, Index p, Index q) {
  EdgeScores s;
  const Vec3 d = P[q] - P[p];
  const double length = d.norm();
  const Vec3 t = d / length;
  const auto side = [&](Index x, double& sin_angle, double& ratio) {
    const std::size_t begin = u.offsets[x], end = u.offsets[x + 1];
    if (begin == end) return;
    double smallest = 1;
    for (std::size_t i = begin; i < end; ++i) smallest = std::min(smallest, std::abs(u.normals[i].dot(t)));
    sin_angle = smallest;
    ratio = length / u.max_radius[x];
  };
  side(p, s.sin_angle_p, s.ratio_p);
  side(q, s.sin_angle_q, s.ratio_q);
  return s;
}

namespace {
int condition_bits(const EdgeScores& s, const MedialOptions& o, double sin_theta) {
  // Angle [θ]: max over U_x of ∠(n, t) < π/2 − θ  ⇔  min |n·t̂| > sin θ (an empty U_x selects nothing).
  // Ratio [ρ]: min over U_x of |pq| / R > ρ  ⇔  |pq| / max R > ρ.
  int bits = 0;
  if (o.angle_condition) {
    if (s.sin_angle_p >= 0 && s.sin_angle_p > sin_theta) bits |= kAngleP;
    if (s.sin_angle_q >= 0 && s.sin_angle_q > sin_theta) bits |= kAngleQ;
  }
  if (o.ratio_condition) {
    if (s.ratio_p >= 0 && s.ratio_p > o.rho) bits |= kRatioP;
    if (s.ratio_q >= 0 && s.ratio_q > o.rho) bits |= kRatioQ;
  }
  return bits;
}
}  // namespace

int conditions(const EdgeScores& s, const MedialOptions& o) { return condition_bits(s, o, std::sin(o.theta)); }

namespace {

struct SelectionBlock {
  std::vector<Selected> selected;
  std::vector<Index> rings;
  std::size_t angle = 0, ratio = 0, unbounded = 0, dropped = 0;
};

/// Whether the edge (p, q) passes a condition at one end: the same tests as
/// condition_bits(score_edge(...)), stopping at the first that decides (most edges fail early).
bool passes_any(const std::vector<Vec3>& P, const Umbrellas& u, Index p, Index q, const MedialOptions& o,
                double sin_theta) {
  const Vec3 d = P[q] - P[p];
  const double length = d.norm();
  const Vec3 t = d / length;
  const Index ends[2] = {p, q};
  if (o.ratio_condition)
    for (Index x : ends)
      if (u.offsets[x] != u.offsets[x + 1] && length / u.max_radius[x] > o.rho) return true;
  if (o.angle_condition)
    for (Index x : ends) {
      const std::size_t begin = u.offsets[x], end = u.offsets[x + 1];
      if (begin == end) continue;
      std::size_t i = begin;
      while (i < end && std::abs(u.normals[i].dot(t)) > sin_theta) ++i;
      if (i == end) return true;
    }
  return false;
}

/// The ring of cells around a Delaunay edge, from the cell that owns it.
struct EdgeRing {
  bool open = false;  ///< a chain between two hull facets (an unbounded facet)
  std::int64_t first_ray = -1, last_ray = -1;  ///< open: hull facet (cell·4 + k) at the chain's two ends
};

/// Walks the ring around edge `edge` (corners u → w) of cell c counter-clockwise about u → w:
/// the cells after c into `forward` (c first), and when the walk leaves through the hull, the
/// chain's other part, walked the other way from c, into `backward`. False when c is not the
/// lowest cell of the ring (or of the chain), the one that owns the edge.
bool walk_owned_ring(const DelaunayTetrahedralization& dt, Index c, int edge, std::vector<Index>& forward,
                     std::vector<Index>& backward, EdgeRing& ring) {
  const auto corners = [&](Index x) -> const std::array<Index, 4>& { return dt.cells[x]; };
  const auto neighbour = [&](Index x, int k) {
    const std::int64_t nb = dt.neighbours[x][k];
    return nb == kInf ? kNone : static_cast<Index>(nb);
  };
  const auto& corner = dt.cells[c];
  const int* e = services::kCellEdges[edge];
  const Index uu = corner[e[0]], ww = corner[e[1]];
  // Orientation: the cells are positively oriented, so crossing first the facet opposite a
  // (cell_edge_sign > 0) or b walks counter-clockwise about u → w.
  const Index a = corner[e[2]], b = corner[e[3]];
  const bool ccw = services::cell_edge_sign(edge) > 0;
  const Index cross = ccw ? a : b, keep = ccw ? b : a;
  forward.assign(1, c);
  Index end_cell = kNone;
  int end_facet = 0;
  const services::RingEnd closed = services::walk_edge_ring(c, uu, ww, cross, keep, corners, neighbour, kNone,
                                                            forward, ~std::size_t{0}, &end_cell, &end_facet);
  if (closed == services::RingEnd::Lower) return false;
  backward.clear();
  ring = EdgeRing{};
  if (closed == services::RingEnd::Boundary) {
    ring.open = true;
    ring.last_ray = static_cast<std::int64_t>(end_cell) * 4 + end_facet;
    if (services::walk_edge_ring(c, uu, ww, keep, cross, corners, neighbour, kNone, backward, ~std::size_t{0},
                                 &end_cell, &end_facet) != services::RingEnd::Boundary)
      return false;
    ring.first_ray = static_cast<std::int64_t>(end_cell) * 4 + end_facet;
  }
  return true;
}

/// Appends a selected edge and its ring (backward reversed, c, forward: counter-clockwise about
/// u → w), turned to run counter-clockwise about p → q when u is not p.
void append_selected(Selected s, bool reversed, const std::vector<Index>& forward, const std::vector<Index>& backward,
                     SelectionBlock& out) {
  s.ring_begin = static_cast<std::uint32_t>(out.rings.size());
  out.rings.insert(out.rings.end(), backward.rbegin(), backward.rend());
  out.rings.insert(out.rings.end(), forward.begin(), forward.end());
  s.ring_size = static_cast<std::uint32_t>(out.rings.size() - s.ring_begin);
  if (reversed) {
    auto first = out.rings.begin() + s.ring_begin, last = out.rings.end();
    if (s.open) {
      std::reverse(first, last);
      std::swap(s.first_ray, s.last_ray);
    } else {
      std::reverse(first + 1, last);  // keep the owner first
    }
  }
  out.selected.push_back(s);
}

/// D–E on the cells begin..end: each edge whose lowest ring cell is here and that passes a
/// condition, with its ring. `original[i]`: the caller's index of point i; p and q of an edge
/// are ordered by it.
void select_block(const std::vector<Vec3>& P, const std::vector<Index>& original, const DelaunayTetrahedralization& dt,
                  const Umbrellas& u, const MedialOptions& options, std::size_t begin, std::size_t end,
                  SelectionBlock& out) {
  std::vector<Index> forward, backward;
  const double sin_theta = std::sin(options.theta);
  for (std::size_t ci = begin; ci < end; ++ci) {
    const Index c = static_cast<Index>(ci);
    const auto& corner = dt.cells[c];
    const auto& nb = dt.neighbours[c];
    for (int edge = 0; edge < 6; ++edge) {
      const int* e = services::kCellEdges[edge];
      // c's two ring neighbours around the edge are across the facets opposite the two other
      // corners: when one is lower, c is not the lowest cell of the ring, which owns the edge.
      const std::int64_t left = nb[e[2]], right = nb[e[3]];
      if ((left != kInf && left < static_cast<std::int64_t>(c)) || (right != kInf && right < static_cast<std::int64_t>(c)))
        continue;
      const Index uu = corner[e[0]], ww = corner[e[1]];
      const bool forward_edge = original[uu] < original[ww];
      const Index p = forward_edge ? uu : ww, q = forward_edge ? ww : uu;
      if (!passes_any(P, u, p, q, options, sin_theta)) continue;
      EdgeRing ring;
      if (!walk_owned_ring(dt, c, edge, forward, backward, ring)) continue;
      // c owns the edge: it is selected. Its scores (fields) and condition bits (label).
      const EdgeScores scores = score_edge(P, u, p, q);
      const int bits = condition_bits(scores, options, sin_theta);
      if (!bits) continue;  // never: passes_any() makes the same tests
      if (bits & (kAngleP | kAngleQ)) ++out.angle;
      if (bits & (kRatioP | kRatioQ)) ++out.ratio;
      if (ring.open) {
        ++out.unbounded;
        if (options.unbounded == Unbounded::Drop) {
          ++out.dropped;
          continue;
        }
      }
      append_selected({p, q, scores, bits, ring.open, 0, 0, ring.first_ray, ring.last_ray}, uu != p, forward,
                      backward, out);
    }
  }
}

/// The blocks' selections concatenated in block order (each block emptied; copied in
/// parallel at offsets fixed beforehand, into arrays that are not zero-filled first), and their
/// counts.
Selection concatenate(std::vector<SelectionBlock>& blocks, bool parallel, MedialReport& info) {
  std::vector<std::size_t> selected_at(blocks.size() + 1, 0), ring_at(blocks.size() + 1, 0);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    selected_at[b + 1] = selected_at[b] + blocks[b].selected.size();
    ring_at[b + 1] = ring_at[b] + blocks[b].rings.size();
    info.selected_angle += blocks[b].angle;
    info.selected_ratio += blocks[b].ratio;
    info.unbounded += blocks[b].unbounded;
    info.unbounded_dropped += blocks[b].dropped;
    info.selected += blocks[b].selected.size() + blocks[b].dropped;
  }
  Selection out{FreshArray<Selected>(selected_at.back()), FreshArray<Index>(ring_at.back())};
  services::for_blocks(blocks.size(), 1, parallel, [&](std::size_t b, std::size_t, std::size_t) {
    const auto shift = static_cast<std::uint32_t>(ring_at[b]);
    for (std::size_t i = 0; i < blocks[b].selected.size(); ++i) {
      Selected s = blocks[b].selected[i];
      s.ring_begin += shift;
      out.selected.construct(selected_at[b] + i, s);
    }
    for (std::size_t i = 0; i < blocks[b].rings.size(); ++i) out.rings.construct(ring_at[b] + i, blocks[b].rings[i]);
    blocks[b] = SelectionBlock{};
  });
  return out;
}

}  // namespace

Selection select_edges(const Renumbered& points, const DelaunayTetrahedralization& dt, const Umbrellas& u,
                       const MedialOptions& options, MedialReport& info) {
  const std::size_t n = dt.cells.size();
  std::vector<SelectionBlock> blocks(services::block_count(n, kBlock));
  services::for_blocks(n, kBlock, options.parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    select_block(points.P, points.original, dt, u, options, begin, end, blocks[b]);
  });
  return concatenate(blocks, options.parallel, info);
}

}  // namespace medax::dey_zhao
