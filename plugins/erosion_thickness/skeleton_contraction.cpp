// The protection of significant cells and the contraction of free pairs outside them (Liu et
// al. 2010, as the ET paper uses it).
#include "skeleton_contraction.hpp"

#include <medax/union_find.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace medax::et::skeleton {

namespace {

/// Wedges with priority > theta2, minus the components (wedges sharing a 1-cell) of area < phi2.
std::vector<char> protect_sheets(const CellComplex& k, const SkeletonOptions& options, Skeleton& out) {
  const std::size_t ne = k.num_cells(), nw = k.num_wedges();
  std::vector<char> prot(nw, 0);
  for (std::size_t w = 0; w < nw; ++w) prot[w] = k.face_prio[k.w_face[w]] > options.theta2;
  UnionFind uf(nw);
  for (std::size_t e = 0; e < ne; ++e) {
    Index first = kNone;
    for (Index i = k.cof_begin[e]; i < k.cof_begin[e + 1]; ++i) {
      const Index w = k.cof[i];
      if (!prot[w]) continue;
      if (first == kNone) first = w;
      else uf.unite(first, w);
    }
  }
  std::vector<double> area(nw, 0.0);
  for (std::size_t w = 0; w < nw; ++w)
    if (prot[w]) area[uf.find(static_cast<Index>(w))] += k.w_area[w];
  std::vector<char> root_seen(nw, 0);
  for (std::size_t w = 0; w < nw; ++w)
    if (prot[w]) {
      const Index r = uf.find(static_cast<Index>(w));
      if (area[r] < options.phi2) {
        if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_sheet_components;
        prot[w] = 0;
      }
    }
  return prot;
}

/// Curve 1-cells with priority > theta1, minus the components (sharing a point) of length < phi1.
std::vector<char> protect_curves(const Subdivision& sub, const CellComplex& k, const SkeletonOptions& options,
                                 Skeleton& out) {
  const std::size_t ne = k.num_cells(), np = sub.num_points();
  std::vector<char> prot(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) prot[e] = k.curve[e] && k.cell_prio[e] > options.theta1;
  UnionFind uf(np);
  for (std::size_t e = 0; e < ne; ++e)
    if (prot[e]) uf.unite(k.ends[e][0], k.ends[e][1]);
  std::vector<double> length(np, 0.0);
  for (std::size_t e = 0; e < ne; ++e)
    if (prot[e]) length[uf.find(k.ends[e][0])] += (sub.point[k.ends[e][0]] - sub.point[k.ends[e][1]]).norm();
  std::vector<char> root_seen(np, 0);
  for (std::size_t e = 0; e < ne; ++e)
    if (prot[e]) {
      const Index r = uf.find(k.ends[e][0]);
      if (length[r] < options.phi1) {
        if (!root_seen[r]) root_seen[r] = 1, ++out.dropped_curve_components;
        prot[e] = 0;
      }
    }
  return prot;
}

}  // namespace

Kept protect(const Subdivision& sub, const CellComplex& k, const SkeletonOptions& options, Skeleton& out) {
  Kept kept;
  kept.w = protect_sheets(k, options, out);
  const std::vector<char> e_protected = protect_curves(sub, k, options, out);
  kept.e = e_protected;
  kept.v.assign(sub.num_points(), 0);
  for (std::size_t w = 0; w < k.num_wedges(); ++w)
    if (kept.w[w]) {
      ++out.protected_faces;
      out.protected_area += k.w_area[w];
      for (Index i = k.w_bnd_begin[w]; i < k.w_bnd_begin[w + 1]; ++i) kept.e[k.w_bnd[i]] = 1;
    }
  for (std::size_t e = 0; e < k.num_cells(); ++e) {
    out.protected_curve_edges += e_protected[e];
    if (kept.e[e]) kept.v[k.ends[e][0]] = kept.v[k.ends[e][1]] = 1;
  }
  return kept;
}

Contraction::Contraction(const CellComplex& k, const Kept& kept, Index num_vertices, std::size_t np)
    : k_(k), kept_(kept), w_alive(k.num_wedges(), 1), e_alive(k.num_cells(), 1), v_alive(np, 0) {
  for (Index v = 0; v < num_vertices; ++v) v_alive[v] = 1;
  for (const Segment& e : k.ends) v_alive[e[0]] = v_alive[e[1]] = 1;
  e_count.resize(k.num_cells());
  v_count.resize(np);
  for (std::size_t e = 0; e < e_count.size(); ++e) e_count[e] = k.cof_begin[e + 1] - k.cof_begin[e];
  for (std::size_t v = 0; v < np; ++v) v_count[v] = k.inc_begin[v + 1] - k.inc_begin[v];
  rank_wedges();
}

void Contraction::run() {
  const Index ne = static_cast<Index>(k_.num_cells()), np = static_cast<Index>(v_alive.size());
  for (Index e = 0; e < ne; ++e) try_edge_wedge(e);
  for (Index v = 0; v < np; ++v) try_vertex_edge(v);
  for (;;) {
    if (!vertex_pairs_.empty()) {
      const Key key = vertex_pairs_.top();
      vertex_pairs_.pop();
      collapse_vertex(static_cast<Index>(key & 0xffffffffu), static_cast<Index>(key >> 32));
    } else if (!wedge_pairs_.empty()) {
      const Key key = wedge_pairs_.top();
      wedge_pairs_.pop();
      collapse_wedge(static_cast<Index>(key & 0xffffffffu), wedge_of_rank_[key >> 32]);
    } else if (!curves_active_) {
      curves_active_ = true;
      for (Index e = 0; e < ne; ++e)
        if (k_.curve[e]) try_edge_wedge(e), try_vertex_edge(k_.ends[e][0]), try_vertex_edge(k_.ends[e][1]);
    } else if (!curve_pairs_.empty()) {
      const Pair p = curve_pairs_.top();
      curve_pairs_.pop();
      if (p.type == 0) collapse_wedge(p.sigma, p.tau);
      else collapse_vertex(p.sigma, p.tau);
    } else {
      break;
    }
  }
}

void Contraction::rank_wedges() {
  const Index F = static_cast<Index>(k_.face_prio.size());
  const std::size_t nw = k_.num_wedges();
  wedge_rank_.resize(nw);
  std::vector<Index> faces(F);
  std::iota(faces.begin(), faces.end(), Index(0));
  std::sort(faces.begin(), faces.end(), [&](Index a, Index b) {
    return k_.face_prio[a] < k_.face_prio[b] || (k_.face_prio[a] == k_.face_prio[b] && a < b);
  });
  Index r = 0;
  for (Index f : faces)
    for (Index w = k_.face_wedge_begin[f]; w < k_.face_wedge_begin[f + 1]; ++w) wedge_rank_[w] = r++;
  wedge_of_rank_.resize(nw);
  for (Index w = 0; w < nw; ++w) wedge_of_rank_[wedge_rank_[w]] = w;
}

void Contraction::try_edge_wedge(Index e) {
  if (!e_alive[e] || e_count[e] != 1 || kept_.e[e]) return;
  for (Index i = k_.cof_begin[e]; i < k_.cof_begin[e + 1]; ++i) {
    const Index w = k_.cof[i];
    if (!w_alive[w]) continue;
    if (kept_.w[w]) return;
    if (!k_.curve[e]) wedge_pairs_.push((Key(wedge_rank_[w]) << 32) | e);
    else if (curves_active_) curve_pairs_.push({1, k_.face_prio[k_.w_face[w]], k_.cell_prio[e], 0, e, w});
    return;
  }
}

void Contraction::try_vertex_edge(Index v) {
  if (!v_alive[v] || v_count[v] != 1 || kept_.v[v]) return;
  for (Index i = k_.inc_begin[v]; i < k_.inc_begin[v + 1]; ++i) {
    const Index e = k_.inc[i];
    if (!e_alive[e]) continue;
    if (e_count[e] != 0 || kept_.e[e]) return;
    if (!k_.curve[e]) vertex_pairs_.push((Key(e) << 32) | v);
    else if (curves_active_) curve_pairs_.push({1, k_.cell_prio[e], kNegInf, 1, v, e});
    return;
  }
}

void Contraction::collapse_wedge(Index e, Index w) {
  if (!w_alive[w] || !e_alive[e] || e_count[e] != 1) return;
  w_alive[w] = 0;
  e_alive[e] = 0;
  for (Index i = k_.w_bnd_begin[w]; i < k_.w_bnd_begin[w + 1]; ++i) --e_count[k_.w_bnd[i]];
  for (Index v : k_.ends[e]) --v_count[v];
  for (Index i = k_.w_bnd_begin[w]; i < k_.w_bnd_begin[w + 1]; ++i) {
    const Index e2 = k_.w_bnd[i];
    if (e2 == e || !e_alive[e2]) continue;
    if (e_count[e2] == 1) try_edge_wedge(e2);
    else if (e_count[e2] == 0) try_vertex_edge(k_.ends[e2][0]), try_vertex_edge(k_.ends[e2][1]);
  }
  for (Index v : k_.ends[e]) try_vertex_edge(v);
}

void Contraction::collapse_vertex(Index v, Index e) {
  if (!v_alive[v] || !e_alive[e] || e_count[e] != 0 || v_count[v] != 1) return;
  v_alive[v] = 0;
  e_alive[e] = 0;
  v_count[v] = 0;
  const Index w = k_.ends[e][0] == v ? k_.ends[e][1] : k_.ends[e][0];
  --v_count[w];
  try_vertex_edge(w);
}

}  // namespace medax::et::skeleton
