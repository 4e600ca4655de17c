// The refined cell complex K of the skeleton: 1-cells (segment pieces, chords, spokes, loose
// edges), 2-cells (wedges), their priorities and incidences.
#include "skeleton_cells.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace medax::et::skeleton {

namespace {

double mean_of(double a, double b) {
  if (std::isinf(a) && a > 0) return a;
  if (std::isinf(b) && b > 0) return b;
  return 0.5 * (a + b);
}

// ---- 1-cells ----

/// Segment pieces (split at the dual point of a used segment) and chords, with their endpoints.
void add_pieces_and_chords(const BurnGraph& g, const Subdivision& sub, CellComplex& k) {
  const Index S = sub.num_segments, F = sub.num_faces();
  k.piece_base.resize(S + 1);
  for (Index s = 0; s < S; ++s) {
    k.piece_base[s] = static_cast<Index>(k.ends.size());
    const auto nodes = sub.segment_nodes(g, s);
    if (sub.segment_used[s]) {
      k.ends.push_back({nodes[0], sub.segment_point(s)});
      k.ends.push_back({sub.segment_point(s), nodes[1]});
    } else {
      k.ends.push_back({nodes[0], nodes[1]});
    }
  }
  k.piece_base[S] = static_cast<Index>(k.ends.size());
  // Chords: endpoints from the faces' sides.
  k.chord_base = static_cast<Index>(k.ends.size());
  k.ends.resize(k.ends.size() + sub.num_chords, Segment{kNone, kNone});
  for (Index f = 0; f < F; ++f) {
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    for (Index j = 0; j < m; ++j)
      if (sub.side_chord[b + j] != kNone)
        k.ends[k.chord_base + sub.side_chord[b + j]] = {sub.corners[b + j], sub.corners[b + (j + 1) % m]};
  }
  k.curve.assign(k.ends.size(), 0);
}

/// The curve edges: the spokes (face dual - point) per face, to become cells with the wedges;
/// a segment dual - unburned node edge marks the piece between them as a curve cell.
void add_spoke_targets(const Subdivision& sub, CellComplex& k) {
  const Index N = sub.num_nodes, S = sub.num_segments, F = sub.num_faces();
  auto is_face_point = [&](Index p) { return p >= N + S; };
  k.spoke_begin.assign(F + 1, 0);
  for (const Segment& e : sub.curve_edges) {
    const bool a = is_face_point(e[0]), b = is_face_point(e[1]);
    if (a != b) ++k.spoke_begin[(a ? e[0] : e[1]) - N - S + 1];
  }
  std::partial_sum(k.spoke_begin.begin(), k.spoke_begin.end(), k.spoke_begin.begin());
  k.spoke_target.resize(k.spoke_begin[F]);
  std::vector<Index> fill(k.spoke_begin.begin(), k.spoke_begin.end() - 1);
  for (const Segment& e : sub.curve_edges) {
    const bool a = is_face_point(e[0]), b = is_face_point(e[1]);
    if (a != b) {
      k.spoke_target[fill[(a ? e[0] : e[1]) - N - S]++] = a ? e[1] : e[0];
    } else if (!a) {  // segment dual - unburned node: the piece between them is a curve edge
      const Index sp = e[0] >= N ? e[0] : e[1], node = e[0] >= N ? e[1] : e[0];
      const Index s = sp - N;
      for (Index c = k.piece_base[s]; c < k.piece_base[s + 1]; ++c)
        if (k.ends[c][0] == node || k.ends[c][1] == node) k.curve[c] = 1;
    }
  }
}

// ---- 2-cells: wedges -----------------------------------------------------------------------------

/// The 1-cell between ring[i] and ring[i+1] of face f, for every i of its ring.
void ring_cells(const Subdivision& sub, const CellComplex& k, Index f, std::vector<Index>& out) {
  out.clear();
  const Index b = sub.face_begin[f], nc = sub.face_begin[f + 1] - b;
  for (Index j = 0; j < nc; ++j) {
    const Index s = sub.side_segment[b + j];
    if (s == kNone) {
      out.push_back(k.chord_base + sub.side_chord[b + j]);
      continue;
    }
    const Index corner = sub.corners[b + j];
    if (!sub.segment_used[s]) {
      out.push_back(k.piece_base[s]);
    } else {
      const bool from_first = k.ends[k.piece_base[s]][0] == corner;
      out.push_back(k.piece_base[s] + (from_first ? 0 : 1));
      out.push_back(k.piece_base[s] + (from_first ? 1 : 0));
    }
  }
}

/// Adds a spoke 1-cell for each spoke of face f, in ring order: `pos` gets their ring positions,
/// `cells` their ids.
void add_face_spokes(const Subdivision& sub, Index f, const std::vector<Index>& ring, CellComplex& k,
                     std::vector<Index>& pos, std::vector<Index>& cells) {
  pos.clear();
  cells.clear();
  const Index m = static_cast<Index>(ring.size());
  for (Index i = 0; i < m; ++i)
    for (Index j = k.spoke_begin[f]; j < k.spoke_begin[f + 1]; ++j)
      if (k.spoke_target[j] == ring[i]) {
        pos.push_back(i);
        cells.push_back(static_cast<Index>(k.ends.size()));
        k.ends.push_back({sub.face_point(f), ring[i]});
        k.curve.push_back(1);
        break;
      }
}

/// Adds the wedge of face f over ring positions first .. first + len (cyclic), bounded by spokes
/// a and b (kNone: none).
void add_wedge(const Subdivision& sub, Index f, const std::vector<Index>& ring, const std::vector<Index>& ring_cell,
               Index first, Index len, Index spoke_a, Index spoke_b, CellComplex& k) {
  const Index m = static_cast<Index>(ring.size());
  const Vec3& c = sub.point[sub.face_point(f)];
  k.w_face.push_back(f);
  k.w_first.push_back(first);
  k.w_len.push_back(len);
  double area = 0;
  if (spoke_a != kNone) k.w_bnd.push_back(spoke_a);
  for (Index i = 0; i < len; ++i) {
    const Index r = (first + i) % m;
    k.w_bnd.push_back(ring_cell[r]);
    area += 0.5 * (sub.point[ring[r]] - c).cross(sub.point[ring[(r + 1) % m]] - c).norm();
  }
  if (spoke_b != kNone) k.w_bnd.push_back(spoke_b);
  k.w_bnd_begin.push_back(static_cast<Index>(k.w_bnd.size()));
  k.w_area.push_back(area);
}

/// Face f's ring b_0..b_{m-1} (corners and used segment duals) is cut by its spokes into wedges;
/// a face with one spoke is one 2-cell whose boundary runs through the spoke twice.
void add_wedges(const Subdivision& sub, CellComplex& k) {
  const Index F = sub.num_faces();
  k.face_wedge_begin.assign(F + 1, 0);
  std::vector<Index> ring, ring_cell, cpos, spoke_cell;
  for (Index f = 0; f < F; ++f) {
    k.face_wedge_begin[f] = static_cast<Index>(k.w_face.size());
    face_boundary_points(sub, f, ring);
    ring_cells(sub, k, f, ring_cell);
    add_face_spokes(sub, f, ring, k, cpos, spoke_cell);
    const Index m = static_cast<Index>(ring.size());
    if (cpos.empty()) {
      add_wedge(sub, f, ring, ring_cell, 0, m, kNone, kNone, k);
      continue;
    }
    const std::size_t n = cpos.size();
    for (std::size_t j = 0; j < n; ++j) {
      const Index a = cpos[j], b = cpos[(j + 1) % n];
      const Index len = n == 1 ? m : (b + m - a) % m;
      add_wedge(sub, f, ring, ring_cell, a, len, spoke_cell[j], spoke_cell[(j + 1) % n], k);
    }
  }
  k.face_wedge_begin[F] = static_cast<Index>(k.w_face.size());
}

// ---- priorities and incidences -------------------------------------------------------------------

void compute_priorities(const Subdivision& sub, const std::vector<double>& et_c, CellComplex& k) {
  const Index F = sub.num_faces();
  k.face_prio.resize(F);
  for (Index f = 0; f < F; ++f) {
    double sum = 0;
    bool inf = false;
    const Index b = sub.face_begin[f], m = sub.face_begin[f + 1] - b;
    for (Index j = b; j < b + m; ++j) {
      const double e = sub.point_et[sub.corners[j]];
      if (std::isinf(e) && e > 0) inf = true;
      sum += e;
    }
    k.face_prio[f] = inf ? kInf : sum / m;
  }
  const std::size_t ne = k.num_cells();
  k.cell_prio.assign(ne, kNegInf);
  for (std::size_t e = 0; e < ne; ++e)
    if (k.curve[e]) k.cell_prio[e] = mean_of(et_c[k.ends[e][0]], et_c[k.ends[e][1]]);
}

/// 1-cell -> wedges (with multiplicity), point -> 1-cells.
void build_incidences(std::size_t np, CellComplex& k) {
  const std::size_t ne = k.num_cells(), nw = k.num_wedges();
  k.cof_begin.assign(ne + 1, 0);
  for (Index c : k.w_bnd) ++k.cof_begin[c + 1];
  std::partial_sum(k.cof_begin.begin(), k.cof_begin.end(), k.cof_begin.begin());
  k.cof.resize(k.cof_begin[ne]);
  std::vector<Index> fill(k.cof_begin.begin(), k.cof_begin.end() - 1);
  for (Index w = 0; w < nw; ++w)
    for (Index i = k.w_bnd_begin[w]; i < k.w_bnd_begin[w + 1]; ++i) k.cof[fill[k.w_bnd[i]]++] = w;
  k.inc_begin.assign(np + 1, 0);
  k.inc.resize(2 * ne);
  for (const Segment& e : k.ends) ++k.inc_begin[e[0] + 1], ++k.inc_begin[e[1] + 1];
  std::partial_sum(k.inc_begin.begin(), k.inc_begin.end(), k.inc_begin.begin());
  fill.assign(k.inc_begin.begin(), k.inc_begin.end() - 1);
  for (std::size_t e = 0; e < ne; ++e)
    for (Index v : k.ends[e]) k.inc[fill[v]++] = static_cast<Index>(e);
}

}  // namespace

CellComplex build_cell_complex(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                               const std::vector<double>& et_c) {
  CellComplex k;
  add_pieces_and_chords(g, sub, k);
  add_spoke_targets(sub, k);
  add_wedges(sub, k);
  for (const Segment& e : loose_edges) {
    k.ends.push_back(e);
    k.curve.push_back(0);
  }
  compute_priorities(sub, et_c, k);
  build_incidences(sub.num_points(), k);
  return k;
}

}  // namespace medax::et::skeleton
