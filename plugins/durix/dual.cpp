#include "dual.hpp"

#include <medax/services/delaunay.hpp>
#include <medax/union_find.hpp>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace medax::durix {

namespace {
std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}
}  // namespace

Dual::Dual(const std::vector<Vec3>& points, const std::vector<Tri>& faces) : points_(points) {
  if (points.size() < 4) throw std::invalid_argument("the mesh has fewer than 4 vertices: no solid to fill");
  services::DelaunayTetrahedralization dt = services::delaunay_tetrahedralize(points);
  if (dt.vertex_point.size() != points.size())
    throw std::invalid_argument(std::to_string(points.size() - dt.vertex_point.size()) +
                                " vertices share the position of another vertex; merge them (`repair`) and run "
                                "`delaunay_surface` again");
  cells_ = std::move(dt.cells);
  nbrs_.resize(dt.neighbours.size());
  for (std::size_t c = 0; c < nbrs_.size(); ++c)
    for (int k = 0; k < 4; ++k)
      nbrs_[c][k] = dt.neighbours[c][k] < 0 ? kNoId : static_cast<CellId>(dt.neighbours[c][k]);
  // Circumcentres in long double, relative to the first corner; flat cells (4 nearly
  // cocircular points: Appendix A) whose sphere cannot be computed take the circumcircle of their
  // largest facet and the mean distance to their corners.
  centres_.resize(cells_.size());
  radii_.resize(cells_.size());
  flat_.assign(cells_.size(), 0);
  for (std::size_t c = 0; c < cells_.size(); ++c) circumsphere(static_cast<CellId>(c));

  // Vertex -> incident cells (CSR).
  voffset_.assign(points.size() + 1, 0);
  for (const auto& q : cells_)
    for (Index v : q) ++voffset_[v + 1];
  for (std::size_t i = 0; i < points.size(); ++i) voffset_[i + 1] += voffset_[i];
  vcells_.resize(voffset_.back());
  {
    std::vector<std::uint32_t> fill(voffset_.begin(), voffset_.end() - 1);
    for (CellId c = 0; c < cells_.size(); ++c)
      for (Index v : cells_[c]) vcells_[fill[v]++] = c;
  }
  classify(faces);
  build_edges();
}

void Dual::circumsphere(CellId cell) {
  using L = long double;
  const auto& q = cells_[cell];
  const Vec3& p0 = points_[q[0]];
  L a[3], b[3], c[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = L(points_[q[1]][i]) - L(p0[i]);
    b[i] = L(points_[q[2]][i]) - L(p0[i]);
    c[i] = L(points_[q[3]][i]) - L(p0[i]);
  }
  const auto cross = [](const L* x, const L* y, L* out) {
    out[0] = x[1] * y[2] - x[2] * y[1];
    out[1] = x[2] * y[0] - x[0] * y[2];
    out[2] = x[0] * y[1] - x[1] * y[0];
  };
  const auto dot = [](const L* x, const L* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  L bc[3], ca[3], ab[3];
  cross(b, c, bc);
  cross(c, a, ca);
  cross(a, b, ab);
  const L det = 2 * dot(a, bc);
  const L na = dot(a, a), nb = dot(b, b), nc = dot(c, c);
  const L scale = std::sqrt(na * nb * nc);
  Vec3 centre;
  bool ok = det != 0 && std::abs(det) > 1e-14L * scale;
  if (ok) {
    for (int i = 0; i < 3; ++i) centre[i] = double(L(p0[i]) + (na * bc[i] + nb * ca[i] + nc * ab[i]) / det);
    ok = centre.allFinite();
  }
  if (!ok) {
    flat_[cell] = 1;
    // Circumcircle of the largest facet.
    double best = -1;
    for (int k = 0; k < 4; ++k) {
      const Vec3& x = points_[q[(k + 1) & 3]];
      const Vec3& y = points_[q[(k + 2) & 3]];
      const Vec3& z = points_[q[(k + 3) & 3]];
      const Vec3 u = y - x, v = z - x, n = u.cross(v);
      const double area2 = n.squaredNorm();
      if (area2 <= best) continue;
      best = area2;
      centre = x + (u.squaredNorm() * v.cross(n) + v.squaredNorm() * n.cross(u)) / (2 * area2);
    }
  }
  double r = 0;
  for (Index v : q) r += (points_[v] - centre).norm();
  centres_[cell] = centre;
  radii_[cell] = r / 4;
}

int Dual::parity(CellId c, Index a, Index b, Index cc, Index d) const {
  const int p[4] = {local(c, a), local(c, b), local(c, cc), local(c, d)};
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
  return (inversions & 1) ? -1 : 1;
}

Dual::SurfaceCells Dual::mark_surface_facets(const std::vector<Tri>& faces) {
  SurfaceCells marks;
  marks.facet_mask.assign(cells_.size(), 0);
  marks.exterior.assign(cells_.size(), 0);
  used_.assign(points_.size(), 0);
  std::size_t missing = 0;
  long long first_missing = -1;
  for (std::size_t fi = 0; fi < faces.size(); ++fi) {
    const Tri& t = faces[fi];
    for (Index v : t)
      if (v >= points_.size()) throw std::invalid_argument("face " + std::to_string(fi) + " refers to a missing vertex");
    for (Index v : t) used_[v] = 1;
    // The (one or two) finite cells having the three corners.
    int found = 0;
    for (const CellId* it = vertex_cells_begin(t[0]); it != vertex_cells_end(t[0]); ++it) {
      const CellId c = *it;
      const int l1 = local(c, t[1]), l2 = local(c, t[2]);
      if (l1 < 0 || l2 < 0) continue;
      const int k = 6 - local(c, t[0]) - l1 - l2;  // the fourth corner
      ++found;
      marks.facet_mask[c] |= std::uint8_t(1u << k);
      // The face is outward: the interior cell has its fourth corner on the negative side.
      if (parity(c, t[0], t[1], t[2], cells_[c][k]) < 0) marks.interior_seeds.push_back(c);
      else marks.exterior[c] = 1;
    }
    if (found == 0 && missing++ == 0) first_missing = static_cast<long long>(fi);
  }
  if (missing)
    throw std::invalid_argument(std::to_string(missing) + " of " + std::to_string(faces.size()) +
                                " faces are not facets of the Delaunay tetrahedralization of the vertices (first: face " +
                                std::to_string(first_missing) +
                                "): the input is not a Delaunay mesh; add a `delaunay_surface` stage before `durix`");
  for (std::size_t v = 0; v < points_.size(); ++v)
    if (!used_[v])
      throw std::invalid_argument("vertex " + std::to_string(v) +
                                  " is used by no face; remove unreferenced vertices (`repair`) first");
  std::sort(marks.interior_seeds.begin(), marks.interior_seeds.end());
  marks.interior_seeds.erase(std::unique(marks.interior_seeds.begin(), marks.interior_seeds.end()),
                             marks.interior_seeds.end());
  return marks;
}

void Dual::flood_interior(const SurfaceCells& marks) {
  solid_.assign(cells_.size(), 0);
  component_.assign(cells_.size(), -1);
  std::vector<CellId> stack;
  for (CellId s : marks.interior_seeds) {
    if (component_[s] >= 0) continue;
    const int comp = num_components_++;
    component_[s] = comp;
    stack.push_back(s);
    while (!stack.empty()) {
      const CellId c = stack.back();
      stack.pop_back();
      if (marks.exterior[c])
        throw std::invalid_argument("the faces do not bound a solid consistently (a cell is both inside and outside); "
                                    "check orientation and self-intersections (`repair`)");
      solid_[c] = 1;
      for (int k = 0; k < 4; ++k) {
        if (marks.facet_mask[c] >> k & 1) continue;
        const CellId n = nbrs_[c][k];
        if (n == kNoId)
          throw std::invalid_argument("the interior reaches the convex hull through a gap: the faces do not close a "
                                      "solid (holes, or faces oriented inward)");
        if (component_[n] < 0) {
          component_[n] = comp;
          stack.push_back(n);
        }
      }
    }
  }
}

void Dual::count_solid_uses() {
  solid_uses_.assign(points_.size(), 0);
  for (CellId c = 0; c < cells_.size(); ++c)
    if (solid_[c])
      for (Index v : cells_[c]) ++solid_uses_[v];
  for (std::size_t v = 0; v < points_.size(); ++v)
    if (!solid_uses_[v])
      throw std::invalid_argument("vertex " + std::to_string(v) + " touches no interior cell: the mesh is not a closed "
                                  "Delaunay surface around a solid");
}

void Dual::classify(const std::vector<Tri>& faces) {
  flood_interior(mark_surface_facets(faces));
  forced_.assign(cells_.size(), 0);
  count_solid_uses();
}

void Dual::build_edges() {
  struct Entry {
    std::uint64_t key;
    CellId cell;
    int pair;
  };
  std::vector<Entry> entries;
  for (CellId c = 0; c < cells_.size(); ++c) {
    if (!solid_[c]) continue;
    for (int p = 0; p < 6; ++p)
      entries.push_back({edge_key(cells_[c][kPairVerts[p][0]], cells_[c][kPairVerts[p][1]]), c, p});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.cell < b.cell; });
  cell_edges_.assign(cells_.size(), {kNoId, kNoId, kNoId, kNoId, kNoId, kNoId});
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i == 0 || entries[i].key != entries[i - 1].key) {
      edge_verts_.push_back({Index(entries[i].key >> 32), Index(entries[i].key & 0xffffffffu)});
      edge_cell_.push_back(entries[i].cell);
    }
    cell_edges_[entries[i].cell][entries[i].pair] = static_cast<EdgeId>(edge_verts_.size() - 1);
  }
  const std::size_t ne = edge_verts_.size();
  ring_size_.assign(ne, 0);
  solid_count_.assign(ne, 0);
  label_.assign(ne, -1);
  std::vector<CellId> ring_cells;
  for (EdgeId e = 0; e < ne; ++e) {
    ring(e, ring_cells);
    if (!ring_cells.empty() && ring_cells.back() == kNoId) {
      ring_size_[e] = 0;
    } else {
      ring_size_[e] = static_cast<std::uint32_t>(ring_cells.size());
    }
    for (CellId c : ring_cells)
      if (c != kNoId && solid_[c]) ++solid_count_[e];
  }
}

void Dual::ring(EdgeId e, std::vector<CellId>& out) const {
  out.clear();
  const Index a = edge_verts_[e][0], b = edge_verts_[e][1];
  const CellId c0 = edge_cell_[e];
  // Walks from c0 across the facet opposite local `first`; returns false on reaching the hull.
  const auto walk = [&](int first_choice, std::vector<CellId>& cells) {
    CellId cur = c0, prev = kNoId;
    for (std::size_t guard = 0; guard < 100000; ++guard) {
      const int la = local(cur, a), lb = local(cur, b);
      int k1 = -1, k2 = -1;
      for (int k = 0; k < 4; ++k)
        if (k != la && k != lb) (k1 < 0 ? k1 : k2) = k;
      const CellId n1 = nbrs_[cur][k1], n2 = nbrs_[cur][k2];
      const CellId nx = prev == kNoId && cur == c0 ? (first_choice == 0 ? n1 : n2) : (n1 == prev ? n2 : n1);
      if (nx == kNoId) return false;
      if (nx == c0) return true;
      cells.push_back(nx);
      prev = cur;
      cur = nx;
    }
    throw std::logic_error("runaway rotation around a Delaunay edge");
  };
  out.push_back(c0);
  if (walk(0, out)) return;
  // On the convex hull: the cells on the other side of c0, then the marker.
  std::vector<CellId> back;
  walk(1, back);
  out.insert(out.begin(), back.rbegin(), back.rend());
  out.push_back(kNoId);
}

void Dual::ring_facets(EdgeId e, std::vector<Facet>& out) const {
  out.clear();
  std::vector<CellId> cells;
  ring(e, cells);
  if (!cells.empty() && cells.back() == kNoId) return;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const CellId c = cells[i], n = cells[(i + 1) % cells.size()];
    for (int k = 0; k < 4; ++k)
      if (nbrs_[c][k] == n) {
        out.push_back(facet(c, k));
        break;
      }
  }
}

void Dual::set_solid(CellId c, bool in) {
  if (bool(solid_[c]) == in) return;
  solid_[c] = in;
  for (int p = 0; p < 6; ++p) {
    const EdgeId e = cell_edges_[c][p];
    if (e == kNoId) throw std::logic_error("a cell without edges changed its solid state");
    if (in) ++solid_count_[e];
    else --solid_count_[e];
  }
  for (Index v : cells_[c]) {
    if (in) ++solid_uses_[v];
    else --solid_uses_[v];
  }
}

Facet Dual::facet(CellId c, int k) const {
  const CellId n = nbrs_[c][k];
  if (n == kNoId || c < n) return {c, std::uint8_t(k)};
  for (int j = 0; j < 4; ++j)
    if (nbrs_[n][j] == c) return {n, std::uint8_t(j)};
  throw std::logic_error("inconsistent cell neighbours");
}

std::array<Index, 3> Dual::facet_vertices(const Facet& f) const {
  const auto& q = cells_[f.cell];
  return {q[(f.k + 1) & 3], q[(f.k + 2) & 3], q[(f.k + 3) & 3]};
}

int Dual::degree(const Facet& f) const {
  const auto v = facet_vertices(f);
  const CellId c = f.cell;
  return int(volumetric(edge_of(c, v[0], v[1]))) + int(volumetric(edge_of(c, v[1], v[2]))) +
         int(volumetric(edge_of(c, v[0], v[2])));
}

void Dual::set_forced(const Facet& f, bool on) {
  const CellId n = other_cell(f);
  int j = -1;
  if (n != kNoId)
    for (int i = 0; i < 4; ++i)
      if (nbrs_[n][i] == f.cell) j = i;
  if (on) {
    forced_[f.cell] |= std::uint8_t(1u << f.k);
    if (j >= 0) forced_[n] |= std::uint8_t(1u << j);
  } else {
    forced_[f.cell] &= std::uint8_t(~(1u << f.k));
    if (j >= 0) forced_[n] &= std::uint8_t(~(1u << j));
  }
}

std::size_t Dual::verify_counters() const {
  std::size_t bad = 0;
  std::vector<CellId> cells;
  for (EdgeId e = 0; e < edge_verts_.size(); ++e) {
    ring(e, cells);
    std::uint32_t count = 0;
    for (CellId c : cells) count += solid(c);
    bad += count != solid_count_[e];
  }
  return bad;
}

void Dual::clear_forced() { std::fill(forced_.begin(), forced_.end(), 0); }
void Dual::clear_labels() { std::fill(label_.begin(), label_.end(), -1); }

Index Dual::third(const HalfEdge& h) const {
  const auto v = facet_vertices(h.t);
  for (Index x : v)
    if (x != h.u && x != h.v) return x;
  throw std::logic_error("malformed half-edge");
}

EdgeId Dual::face(const HalfEdge& h) const { return edge_of(h.t.cell, h.u, h.v); }

CellId Dual::start(const HalfEdge& h) const {
  const Index w = third(h);
  const CellId c = h.t.cell;
  const Index d = cells_[c][h.t.k];
  return parity(c, h.u, h.v, w, d) > 0 ? c : other_cell(h.t);
}

CellId Dual::end(const HalfEdge& h) const {
  const CellId s = start(h);
  return s == h.t.cell ? other_cell(h.t) : h.t.cell;
}

HalfEdge Dual::next(const HalfEdge& h) const {
  const CellId n = end(h);
  const Index w = third(h);
  return {facet(n, local(n, w)), h.u, h.v};
}

HalfEdge Dual::prev(const HalfEdge& h) const {
  const CellId n = start(h);
  const Index w = third(h);
  return {facet(n, local(n, w)), h.u, h.v};
}

HalfEdge Dual::side_nbr(const HalfEdge& h) const {
  HalfEdge g = cell_nbr(h);
  for (int i = 0; i < 3 && !volumetric(face(g)); ++i) g = cell_nbr(flip(g));
  return g;
}

int Dual::node_components(CellId c) const {
  UnionFind corners(4);
  for (int p = 0; p < 6; ++p)
    if (!volumetric(cell_edges_[c][p])) corners.unite(kPairVerts[p][0], kPairVerts[p][1]);
  return static_cast<int>(corners.count());
}

std::vector<Facet> Dual::surface_facets() const {
  std::vector<Facet> out;
  for (CellId c = 0; c < cells_.size(); ++c) {
    if (!solid_[c]) continue;
    for (int k = 0; k < 4; ++k)
      if (!solid(nbrs_[c][k])) out.push_back(facet(c, k));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Tri Dual::oriented_surface_triangle(const Facet& f) const {
  CellId s = f.cell;
  int k = f.k;
  if (!solid(s)) {
    const CellId n = other_cell(f);
    for (int j = 0; j < 4; ++j)
      if (nbrs_[n][j] == s) k = j;
    s = n;
  }
  const auto& q = cells_[s];
  Tri t{q[(k + 1) & 3], q[(k + 2) & 3], q[(k + 3) & 3]};
  if (parity(s, t[0], t[1], t[2], q[k]) > 0) std::swap(t[1], t[2]);
  return t;
}

}  // namespace medax::durix
