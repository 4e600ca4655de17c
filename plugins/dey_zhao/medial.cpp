#include "medial.hpp"

#include "inner.hpp"

#include <medax/services/blocks.hpp>
#include <medax/services/delaunay_rings.hpp>
#include <medax/union_find.hpp>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>

namespace medax::dey_zhao {

const std::vector<std::pair<std::string, InnerSelection>>& inner_selection_names() {
  static const std::vector<std::pair<std::string, InnerSelection>> names{
      {"auto", InnerSelection::Auto},
      {"delaunay_surface", InnerSelection::DelaunaySurface},
      {"mesh", InnerSelection::Mesh},
      {"normals", InnerSelection::Normals},
      {"none", InnerSelection::None},
  };
  return names;
}

const char* to_string(InnerSelection s) {
  for (const auto& [name, value] : inner_selection_names())
    if (value == s) return name.c_str();
  return "?";
}

namespace {

using services::DelaunayTetrahedralization;
using Clock = std::chrono::steady_clock;
constexpr std::int64_t kInf = DelaunayTetrahedralization::kInfinite;
constexpr Index kNone = ~Index{0};
constexpr std::size_t kBlock = 4096;  // cells per parallel work unit (fixed: output independent of the schedule)

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// The three corners of facet k of a cell, in increasing position order.
inline std::array<Index, 3> facet_corners(const std::array<Index, 4>& corner, int k) {
  std::array<Index, 3> f{};
  for (int j = 0, m = 0; j < 4; ++j)
    if (j != k) f[m++] = corner[j];
  return f;
}

/// Normal of facet k of a positively oriented cell, pointing out of the cell (not normalised).
/// The direction comes from the cell's orientation (exact), not from a floating-point test.
inline Vec3 outward_normal(const std::vector<Vec3>& P, const std::array<Index, 4>& corner, int k) {
  const auto f = facet_corners(corner, k);
  const Vec3 n = (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]);
  // (f0, f1, f2, corner k) is the permutation moving k last: sign (-1)^(3-k). When positive,
  // corner k is on the side n points to, so n points inwards.
  return (k % 2 == 1) ? Vec3(-n) : n;
}

inline Vec3 unit(const Vec3& v) {
  const double norm = v.norm();
  return norm > 0 ? Vec3(v / norm) : Vec3::Zero();
}

/// Circumradius of the triangle (a, b, c): |u||v||u − v| / (2 |u × v|), u = b − a, v = c − a.
inline double circumradius(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a;
  const double area2 = u.cross(v).norm();
  return area2 > 0 ? u.norm() * v.norm() * (u - v).norm() / (2 * area2) : std::numeric_limits<double>::infinity();
}

/// max on non-negative doubles stored as their bit patterns (monotone for x ≥ 0, +inf included).
inline void atomic_max(std::atomic<std::uint64_t>& slot, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  std::uint64_t current = slot.load(std::memory_order_relaxed);
  while (bits > current && !slot.compare_exchange_weak(current, bits, std::memory_order_relaxed)) {
  }
}

/// The points' indices along a Morton (Z-order) curve of their bounding box, ties by index.
/// Computing in that order keeps the per-point arrays and the cells (sorted by corners) local in
/// memory; samples often come in random order. The codes depend on coordinates only through
/// comparisons and the ratios (x − lo) / (hi − lo), so scaling by a power of two keeps them.
std::vector<Index> spatial_order(const std::vector<Vec3>& P, bool parallel) {
  const std::size_t n = P.size();
  std::vector<Index> order(n);
  if (n == 0) return order;
  Vec3 lo = P[0], hi = P[0];
  for (const Vec3& p : P) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const auto spread = [](std::uint64_t v) {  // 21 bits to every third bit
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::vector<std::pair<std::uint64_t, Index>> keys(n);
  const auto key = [&](std::size_t i) {
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double extent = hi[a] - lo[a];
      const double f = extent > 0 ? (P[i][a] - lo[a]) / extent : 0.0;
      const auto q = static_cast<std::uint64_t>(std::min(2097151.0, std::max(0.0, std::floor(f * 2097152.0))));
      code |= spread(q) << a;
    }
    keys[i] = {code, static_cast<Index>(i)};
  };
  if (parallel) {
    tbb::parallel_for(std::size_t{0}, n, key);
    tbb::parallel_sort(keys.begin(), keys.end());
  } else {
    for (std::size_t i = 0; i < n; ++i) key(i);
    std::sort(keys.begin(), keys.end());
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].second;
  return order;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Passes B–C: poles and umbrellas.

namespace {

/// B. Pole: the farthest Voronoi vertex of V_p (ties: the lowest cell). On the hull, V_p is
/// unbounded: v_p is the normalised sum of the unit outward normals of the hull facets at p,
/// the directions of V_p's infinite edges. Fills u.pole_vector and u.on_hull.
void compute_poles(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, Umbrellas& u) {
  const std::size_t n = dt.cells.size(), np = P.size();
  const auto& cc = dt.circumcentres;
  std::vector<double> best(np, -1.0);
  std::vector<Index> farthest(np, kNone);
  std::vector<Vec3> hull(np, Vec3::Zero());
  u.on_hull.assign(np, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const auto& corner = dt.cells[c];
    for (int k = 0; k < 4; ++k) {
      const Index x = corner[k];
      const double d2 = (cc[c] - P[x]).squaredNorm();
      if (d2 > best[x]) best[x] = d2, farthest[x] = static_cast<Index>(c);
    }
    for (int k = 0; k < 4; ++k)
      if (dt.neighbours[c][k] == kInf) {
        const Vec3 nt = unit(outward_normal(P, corner, k));
        for (int j = 0; j < 4; ++j)
          if (j != k) hull[corner[j]] += nt, u.on_hull[corner[j]] = 1;
      }
  }
  u.pole_vector.resize(np);
  for (std::size_t x = 0; x < np; ++x)
    u.pole_vector[x] = u.on_hull[x] ? unit(hull[x])
                       : farthest[x] != kNone ? unit(cc[farthest[x]] - P[x])
                                              : Vec3(Vec3::Zero());
}

/// Which Delaunay facets are in which umbrellas, and per point its umbrella's size and largest
/// circumradius.
struct UmbrellaFacets {
  std::vector<std::uint16_t> mask;  ///< per cell, bit 3k + m: facet k is in the umbrella of its m-th corner
  std::unique_ptr<std::atomic<std::uint32_t>[]> count;       ///< per point: umbrella triangles
  std::unique_ptr<std::atomic<std::uint64_t>[]> max_radius;  ///< per point: bits of the largest circumradius
};

/// C. Umbrella of p: the Delaunay triangles at p whose dual Voronoi edge crosses the plane
/// through p normal to v_p. sgn'(x) = (x >= 0 ? + : −) is an infinitesimally shifted plane.
/// Each facet is visited once, from its lower cell (or its only finite cell on the hull).
UmbrellaFacets find_umbrella_facets(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt,
                                    const std::vector<Vec3>& v, bool parallel) {
  const std::size_t n = dt.cells.size(), np = P.size();
  const auto& cc = dt.circumcentres;
  UmbrellaFacets out;
  out.count = std::make_unique<std::atomic<std::uint32_t>[]>(np);
  out.max_radius = std::make_unique<std::atomic<std::uint64_t>[]>(np);
  out.mask.assign(n, 0);
  services::for_blocks(n, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const auto& corner = dt.cells[c];
      std::uint16_t bits = 0;
      for (int k = 0; k < 4; ++k) {
        const std::int64_t nb = dt.neighbours[c][k];
        if (nb != kInf && nb < static_cast<std::int64_t>(c)) continue;
        const auto f = facet_corners(corner, k);
        Vec3 ray = Vec3::Zero();
        if (nb == kInf) ray = outward_normal(P, corner, k);
        int hits = 0;
        for (int m = 0; m < 3; ++m) {
          const Index x = f[m];
          const double s1 = (cc[c] - P[x]).dot(v[x]);
          const double s2 = nb == kInf ? ray.dot(v[x]) : (cc[nb] - P[x]).dot(v[x]);
          if ((s1 >= 0) != (s2 >= 0)) bits |= static_cast<std::uint16_t>(1u << (3 * k + m)), ++hits;
        }
        if (!hits) continue;
        const double r = circumradius(P[f[0]], P[f[1]], P[f[2]]);
        for (int m = 0; m < 3; ++m)
          if (bits & (1u << (3 * k + m))) {
            out.count[f[m]].fetch_add(1, std::memory_order_relaxed);
            atomic_max(out.max_radius[f[m]], r);
          }
      }
      out.mask[c] = bits;
    }
  });
  return out;
}

/// C, stored: the umbrellas as flat arrays (offsets per point, unit normals, triangles when
/// asked for) and the largest circumradius per point.
void fill_umbrellas(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, UmbrellaFacets& facets,
                    bool keep_triangles, bool parallel, Umbrellas& u) {
  const std::size_t n = dt.cells.size(), np = P.size();
  auto& count = facets.count;
  const auto& mask = facets.mask;
  u.offsets.assign(np + 1, 0);
  u.max_radius.resize(np);
  for (std::size_t x = 0; x < np; ++x) {
    u.offsets[x + 1] = u.offsets[x] + count[x].load(std::memory_order_relaxed);
    const std::uint64_t bits = facets.max_radius[x].load(std::memory_order_relaxed);
    std::memcpy(&u.max_radius[x], &bits, sizeof bits);
  }
  u.normals.resize(u.offsets[np]);
  if (keep_triangles) u.triangles.resize(u.offsets[np]);
  for (std::size_t x = 0; x < np; ++x) count[x].store(0, std::memory_order_relaxed);  // reused as cursors
  services::for_blocks(n, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      if (!mask[c]) continue;
      const auto& corner = dt.cells[c];
      for (int k = 0; k < 4; ++k) {
        if (!((mask[c] >> (3 * k)) & 7u)) continue;
        const auto f = facet_corners(corner, k);
        const Vec3 normal = unit((P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]));
        for (int m = 0; m < 3; ++m)
          if (mask[c] & (1u << (3 * k + m))) {
            const std::size_t slot = u.offsets[f[m]] + count[f[m]].fetch_add(1, std::memory_order_relaxed);
            u.normals[slot] = normal;
            if (keep_triangles) u.triangles[slot] = {f[0], f[1], f[2]};
          }
      }
    }
  });
}

}  // namespace

Umbrellas compute_umbrellas(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, bool keep_triangles,
                            bool parallel) {
  Umbrellas u;
  compute_poles(P, dt, u);
  UmbrellaFacets facets = find_umbrella_facets(P, dt, u.pole_vector, parallel);
  fill_umbrellas(P, dt, facets, keep_triangles, parallel, u);
  return u;
}

// ---------------------------------------------------------------------------------------------
// Pass D: the conditions.

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

/// A selected Delaunay edge with the ring of cells around it, oriented along p → q.
struct Selected {
  Index p, q;
  EdgeScores scores;
  int bits;
  bool open;                  ///< unbounded facet: the ring is a chain between two hull facets
  std::uint32_t ring_begin, ring_size;
  std::int64_t first_ray = -1, last_ray = -1;  ///< open: hull facet (cell·4 + k) at the ring's front and back
};

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

// ---------------------------------------------------------------------------------------------
// MEDIAL, pass by pass.

/// The points renumbered along a space-filling curve (locality): every pass runs on them, and
/// `original` maps back to the caller's indices for the output.
struct Renumbered {
  std::vector<Index> original;  ///< original[i]: the caller's index of point i
  std::vector<Vec3> P;
  bool has_normals = false;  ///< the input has one normal per point
  std::vector<Vec3> normals;  ///< ... renumbered
};

Renumbered renumber_points(const MedialInput& input, bool parallel) {
  Renumbered r;
  r.original = spatial_order(*input.points, parallel);
  r.P.resize(r.original.size());
  for (std::size_t i = 0; i < r.P.size(); ++i) r.P[i] = (*input.points)[r.original[i]];
  r.has_normals = input.normals && input.normals->size() == r.P.size();
  if (r.has_normals) {
    r.normals.resize(r.P.size());
    for (std::size_t i = 0; i < r.P.size(); ++i) r.normals[i] = (*input.normals)[r.original[i]];
  }
  return r;
}

/// The inner selection asked for, what it can use, and the mesh test built alongside the
/// Delaunay tetrahedralization.
struct InnerSetup {
  InnerSelection inner = InnerSelection::Auto;  ///< as requested (pass F resolves Auto)
  bool has_mesh = false;
  bool try_surface = false;   ///< DelaunaySurface may apply: tried once the cells are known
  bool prepare_mesh = false;  ///< build the mesh test alongside the tetrahedralization
  std::optional<MeshEdgeSide> mesh_side;
  std::string mesh_side_error;  ///< why the mesh test could not be built
};

/// Refuses an inner selection that lacks its data, and plans the setup of the one that can run.
InnerSetup plan_inner(const MedialInput& input, const Renumbered& points, InnerSelection inner) {
  InnerSetup s;
  s.inner = inner;
  s.has_mesh = input.mesh && !input.mesh->faces.empty();
  if (inner == InnerSelection::DelaunaySurface && !(s.has_mesh && input.points_are_mesh_vertices))
    throw std::invalid_argument("inner selection `delaunay_surface` needs the mesh, with the points being its "
                                "vertices (`points: vertices`)");
  if (inner == InnerSelection::Mesh && !s.has_mesh)
    throw std::invalid_argument("inner selection `mesh` needs a surface mesh");
  if (inner == InnerSelection::Normals && !points.has_normals)
    throw std::invalid_argument("inner selection `normals` needs one outward normal per point");
  s.try_surface = (inner == InnerSelection::Auto || inner == InnerSelection::DelaunaySurface) && s.has_mesh &&
                  input.points_are_mesh_vertices;
  s.prepare_mesh = inner == InnerSelection::Mesh || (inner == InnerSelection::Auto && s.has_mesh && !s.try_surface);
  return s;
}

/// Builds the mesh test when planned (an open mesh is refused under Mesh, noted under Auto).
void prepare_mesh_side(const MedialInput& input, InnerSetup& s) {
  if (!s.prepare_mesh) return;
  try {
    s.mesh_side.emplace(*input.mesh);
  } catch (const std::invalid_argument& e) {
    if (s.inner == InnerSelection::Mesh) throw;
    s.mesh_side_error = e.what();
  }
}

/// A. The Delaunay tetrahedralization and its circumcentres, the mesh test built alongside.
DelaunayTetrahedralization tetrahedralize(const Renumbered& points, const MedialInput& input, bool parallel,
                                          InnerSetup& inner, MedialReport& info) {
  DelaunayTetrahedralization dt = services::delaunay_tetrahedralize_alongside(
      points.P, {parallel}, [&] { prepare_mesh_side(input, inner); });
  const std::size_t n = dt.cells.size();
  if (n >= kNone / 4) throw std::invalid_argument("too many Delaunay cells for 32-bit indices");
  info.points = dt.vertex_point.size();
  info.cells = n;
  return dt;
}

/// After B–C: the points on the hull, the empty umbrellas and the number of Delaunay edges.
void count_umbrellas(const DelaunayTetrahedralization& dt, const Umbrellas& u, MedialReport& info) {
  const std::size_t n = dt.cells.size();
  std::size_t hull_facets = 0;
  for (const auto& nb : dt.neighbours)
    for (std::int64_t x : nb) hull_facets += x == kInf;
  for (Index x : dt.vertex_point) {
    info.hull_points += u.on_hull[x] != 0;
    info.empty_umbrellas += u.size(x) == 0;
  }
  // Euler: V − E + F − C = 1 for a triangulated ball, with F = (4C + H) / 2.
  info.delaunay_edges = info.points + (4 * n + hull_facets) / 2 - n - 1;
}

/// The selected edges, in block order, with the rings of cells around them.
struct Selection {
  std::vector<Selected> selected;
  std::vector<Index> rings;  ///< selected[i]'s ring: ring_size cells from ring_begin
};

/// The blocks' selections concatenated in block order (each block emptied), and their counts.
Selection concatenate(std::vector<SelectionBlock>& blocks, MedialReport& info) {
  Selection out;
  std::size_t count = 0, ring_total = 0;
  for (const auto& b : blocks) count += b.selected.size(), ring_total += b.rings.size();
  out.selected.reserve(count);
  out.rings.reserve(ring_total);
  for (auto& b : blocks) {
    const auto shift = static_cast<std::uint32_t>(out.rings.size());
    for (Selected s : b.selected) {
      s.ring_begin += shift;
      out.selected.push_back(s);
    }
    out.rings.insert(out.rings.end(), b.rings.begin(), b.rings.end());
    info.selected_angle += b.angle;
    info.selected_ratio += b.ratio;
    info.unbounded += b.unbounded;
    info.unbounded_dropped += b.dropped;
    info.selected += b.selected.size() + b.dropped;
    b = SelectionBlock{};
  }
  return out;
}

/// D–E. The conditions on every edge, from the lowest cell of its ring; rings of the selected.
Selection select_edges(const Renumbered& points, const DelaunayTetrahedralization& dt, const Umbrellas& u,
                       const MedialOptions& options, MedialReport& info) {
  const std::size_t n = dt.cells.size();
  std::vector<SelectionBlock> blocks(services::block_count(n, kBlock));
  services::for_blocks(n, kBlock, options.parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    select_block(points.P, points.original, dt, u, options, begin, end, blocks[b]);
  });
  return concatenate(blocks, info);
}

/// The mesh triangles in the renumbered point indices (indices past the points left as they are).
SurfaceMesh renumber_mesh(const SurfaceMesh& mesh, const std::vector<Index>& original) {
  const std::size_t np = original.size();
  std::vector<Index> position(np);
  for (std::size_t i = 0; i < np; ++i) position[original[i]] = static_cast<Index>(i);
  const auto at = [&](Index v) { return v < np ? position[v] : v; };
  SurfaceMesh renumbered;
  renumbered.faces.reserve(mesh.faces.size());
  for (const Tri& f : mesh.faces) renumbered.faces.push_back({at(f[0]), at(f[1]), at(f[2])});
  return renumbered;
}

/// F (a): labels the cells inside (1) by the mesh triangles when they are all Delaunay facets.
/// When they are not, DelaunaySurface is refused, and Auto notes why and builds the mesh test.
bool label_cells(const Renumbered& points, const MedialInput& input, const DelaunayTetrahedralization& dt,
                 InnerSetup& setup, std::vector<char>& cell_inside, MedialReport& info) {
  std::size_t missing = 0;
  bool labelled = false;
  try {
    labelled = label_cells_by_surface(dt, renumber_mesh(*input.mesh, points.original), cell_inside, missing);
  } catch (const std::invalid_argument&) {
    if (setup.inner == InnerSelection::DelaunaySurface) throw;
    info.inner_note = "the mesh triangles are Delaunay facets but their inside parity is inconsistent; ";
  }
  if (labelled) {
    info.inner_note += "every mesh triangle is a Delaunay facet";
    return true;
  }
  if (setup.inner == InnerSelection::DelaunaySurface)
    throw std::invalid_argument("inner selection `delaunay_surface`: " + std::to_string(missing) + " of " +
                                std::to_string(input.mesh->faces.size()) +
                                " mesh triangles are not Delaunay facets of the points; use `inner: mesh`");
  if (missing) info.inner_note += std::to_string(missing) + " mesh triangles are not Delaunay facets; ";
  try {
    setup.mesh_side.emplace(*input.mesh);
  } catch (const std::invalid_argument& e) {
    setup.mesh_side_error = e.what();
  }
  return false;
}

/// F, `auto` without Delaunay mesh triangles: the mesh test when the mesh is closed, else the
/// normals, else none.
InnerSelection choose_inner(const InnerSetup& setup, bool has_normals, MedialReport& info) {
  if (setup.mesh_side) {
    info.inner_note += "general closed mesh";
    return InnerSelection::Mesh;
  }
  const std::string unusable = setup.has_mesh ? "mesh unusable (" + setup.mesh_side_error + "); " : std::string();
  if (has_normals) {
    info.inner_note += unusable + "oriented normals";
    return InnerSelection::Normals;
  }
  info.inner_note += unusable + "no mesh and no normals: inner and outer medial axis";
  return InnerSelection::None;
}

/// Whether every Voronoi vertex of the facet dual to `s` lies within the points' bounding box
/// [lo, hi]: the inner medial axis does, while a nearly flat cell on the surface has its
/// circumcentre far off along the normal, on either side (Normals has no mesh to reject it).
bool facet_in_box(const Selected& s, const Selection& selection, const DelaunayTetrahedralization& dt,
                  const Vec3& lo, const Vec3& hi) {
  for (std::uint32_t k = 0; k < s.ring_size; ++k) {
    const Vec3& c = dt.circumcentres[selection.rings[s.ring_begin + k]];
    if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) return false;
  }
  return true;
}

/// F: 1 for each selected edge that `inner` keeps.
std::vector<char> keep_inner(InnerSelection inner, const Renumbered& points, const Selection& selection,
                             const std::vector<char>& cell_inside, const InnerSetup& setup,
                             const DelaunayTetrahedralization& dt, bool parallel) {
  const std::vector<Vec3>& P = points.P;
  const std::vector<Selected>& selected = selection.selected;
  std::vector<char> keep(selected.size(), 1);
  switch (inner) {
    case InnerSelection::DelaunaySurface:
      for (std::size_t i = 0; i < selected.size(); ++i) {
        const Selected& s = selected[i];
        bool all = !s.open;
        for (std::uint32_t k = 0; k < s.ring_size && all; ++k)
          all = cell_inside[selection.rings[s.ring_begin + k]] != 0;
        keep[i] = all;
      }
      break;
    case InnerSelection::Mesh: {
      std::vector<std::array<Index, 2>> edges(selected.size());
      for (std::size_t i = 0; i < selected.size(); ++i) edges[i] = {selected[i].p, selected[i].q};
      keep = setup.mesh_side->inner(P, edges, parallel);
      break;
    }
    case InnerSelection::Normals: {
      const auto& N = points.normals;
      Vec3 lo = P[dt.vertex_point[0]], hi = lo;
      for (Index x : dt.vertex_point) lo = lo.cwiseMin(P[x]), hi = hi.cwiseMax(P[x]);
      for (std::size_t i = 0; i < selected.size(); ++i) {
        const Selected& s = selected[i];
        const Vec3 d = P[s.q] - P[s.p];
        keep[i] = N[s.p].dot(d) < 0 && N[s.q].dot(d) > 0 && facet_in_box(s, selection, dt, lo, hi);
      }
      break;
    }
    default: break;
  }
  return keep;
}

/// F. Inner/outer selection: which selected facets are kept; the report says which selection
/// ran, why, and how many it rejected.
std::vector<char> select_inner(const Renumbered& points, const MedialInput& input, const DelaunayTetrahedralization& dt,
                               const Selection& selection, InnerSetup& setup, bool parallel, MedialReport& info) {
  InnerSelection inner = setup.inner;
  std::vector<char> cell_inside;
  if (setup.try_surface && label_cells(points, input, dt, setup, cell_inside, info))
    inner = InnerSelection::DelaunaySurface;
  if (inner == InnerSelection::Auto) inner = choose_inner(setup, points.has_normals, info);
  info.inner_used = inner;
  std::vector<char> keep = keep_inner(inner, points, selection, cell_inside, setup, dt, parallel);
  for (char k : keep) info.outer += !k;
  return keep;
}

// ---------------------------------------------------------------------------------------------
// The output complex: facets with shared Voronoi vertices, fan-triangulated, and their closure.

/// Diagonal of the bounding box of the points in the tetrahedralization.
double bbox_diagonal(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt) {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  if (!P.empty())
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = P[dt.vertex_point[0]][a];
  for (Index x : dt.vertex_point)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], P[x][a]), hi[a] = std::max(hi[a], P[x][a]);
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// Facet vertices closer than the tolerance are merged (cospherical points: many cells, one
/// circumcentre); each class is represented by its lowest cell. Empty when nothing merges.
std::optional<UnionFind> merge_close_cells(const Selection& selection, const std::vector<char>& keep,
                                           const DelaunayTetrahedralization& dt, double tolerance) {
  const auto& cc = dt.circumcentres;
  std::optional<UnionFind> classes;
  for (std::size_t i = 0; i < selection.selected.size(); ++i) {
    if (!keep[i]) continue;
    const Selected& s = selection.selected[i];
    const Index* r = selection.rings.data() + s.ring_begin;
    for (std::uint32_t k = 0; k < s.ring_size; ++k) {
      if (s.open && k + 1 == s.ring_size) break;  // no Voronoi edge between the chain's two ends
      const Index a = r[k], b = r[(k + 1) % s.ring_size];
      if (a != b && (cc[a] - cc[b]).norm() <= tolerance) {
        if (!classes) classes.emplace(dt.cells.size());
        classes->unite(a, b);
      }
    }
  }
  return classes;
}

/// The output vertices of the cells.
struct CellVertices {
  std::vector<Index> of_cell;  ///< per cell: its vertex (a merged cell: its class's), kNone if unused
  std::vector<Index> cell;     ///< per vertex: its cell
};

/// Vertex numbering: the cells around kept facets in cell order, each merge class numbered once
/// (by its lowest cell, one of the used cells, which stands for the others).
CellVertices number_cells(const Selection& selection, const std::vector<char>& keep, std::size_t n,
                          std::optional<UnionFind>& classes, MedialReport& info) {
  CellVertices out;
  out.of_cell.assign(n, kNone);
  for (std::size_t i = 0; i < selection.selected.size(); ++i) {
    if (!keep[i]) continue;
    const Selected& s = selection.selected[i];
    for (std::uint32_t k = 0; k < s.ring_size; ++k) out.of_cell[selection.rings[s.ring_begin + k]] = 0;
  }
  std::vector<Index> merged;
  if (classes)
    for (std::size_t c = 0; c < n; ++c)
      if (out.of_cell[c] != kNone && classes->find(static_cast<Index>(c)) != c) {
        out.of_cell[c] = kNone;
        merged.push_back(static_cast<Index>(c));
      }
  info.merged_vertices += merged.size();
  for (std::size_t c = 0; c < n; ++c)
    if (out.of_cell[c] != kNone) {
      out.of_cell[c] = static_cast<Index>(out.cell.size());
      out.cell.push_back(static_cast<Index>(c));
    }
  for (Index c : merged) out.of_cell[c] = out.of_cell[classes->find(c)];
  return out;
}

/// The vertices of the used cells: circumcentre, circumradius (the Delaunay ball), generators =
/// the cell's 4 corners (sorted). The complex has no vertex column yet: its vectors are filled
/// in place, in parallel.
void add_cell_vertices(MedialComplex& medial, const CellVertices& cells, const DelaunayTetrahedralization& dt,
                       const std::vector<Index>& original, bool parallel) {
  const std::size_t nv = cells.cell.size();
  medial.centres.resize(nv);
  medial.radii.resize(nv);
  medial.generators.resize(nv);
  services::for_blocks(nv, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Index c = cells.cell[v];
      medial.centres[v] = dt.circumcentres[c];
      medial.radii[v] = dt.circumradii[c];
      std::array<Index, 4> g;
      for (int k = 0; k < 4; ++k) g[k] = original[dt.cells[c][k]];
      std::sort(g.begin(), g.end());
      medial.generators[v].assign(g.begin(), g.end());
    }
  });
}

/// The clipped ray ends (Unbounded::Clip): their vertices follow the cells' vertices.
struct RayVertices {
  std::vector<std::int64_t> rays;  ///< hull facets (cell·4 + k) of the kept rays, sorted, each once
  Index first = 0;                 ///< the vertex of rays[0]

  Index of(std::int64_t ray) const {
    return first + static_cast<Index>(std::lower_bound(rays.begin(), rays.end(), ray) - rays.begin());
  }
  bool is_ray(Index vertex) const { return vertex >= first; }
};

/// Adds a vertex at each kept ray's end, clip_factor bounding-box diagonals from its
/// circumcentre along the hull facet's normal; generators = the hull facet's 3 corners.
RayVertices add_ray_vertices(MedialComplex& medial, const Selection& selection, const std::vector<char>& keep,
                             const DelaunayTetrahedralization& dt, const Renumbered& points, double ray_length) {
  RayVertices out;
  for (std::size_t i = 0; i < selection.selected.size(); ++i) {
    const Selected& s = selection.selected[i];
    if (keep[i] && s.open) out.rays.push_back(s.first_ray), out.rays.push_back(s.last_ray);
  }
  std::sort(out.rays.begin(), out.rays.end());
  out.rays.erase(std::unique(out.rays.begin(), out.rays.end()), out.rays.end());
  out.first = static_cast<Index>(medial.num_vertices());
  for (std::int64_t ray : out.rays) {
    const Index c = static_cast<Index>(ray / 4);
    const int k = static_cast<int>(ray % 4);
    const auto f = facet_corners(dt.cells[c], k);
    const Vec3 end = dt.circumcentres[c] + ray_length * unit(outward_normal(points.P, dt.cells[c], k));
    const Index v = medial.add_vertex(end, (end - points.P[f[0]]).norm());
    std::array<Index, 3> g{points.original[f[0]], points.original[f[1]], points.original[f[2]]};
    std::sort(g.begin(), g.end());
    medial.generators[v].assign(g.begin(), g.end());
  }
  return out;
}

/// An edge of the closure, before sorting and deduplication.
struct EdgeRecord {
  Index a, b;
  int diagonal, clipped;
  bool operator<(const EdgeRecord& o) const {
    return a != o.a ? a < o.a : b != o.b ? b < o.b : diagonal != o.diagonal ? diagonal < o.diagonal : clipped > o.clipped;
  }
};

/// The triangles, face labels and fields, and edges of one block of kept facets.
struct FacetBlock {
  std::vector<Tri> faces;
  std::vector<int> polygon, p, q, conditions, unbounded;
  std::vector<double> angle, ratio;
  std::vector<EdgeRecord> edges;
  int facets = 0, degenerate = 0;
};

/// The vertex cycle of a kept facet around p → q: its cells' vertices (consecutive repeats after
/// merging dropped), between its two ray ends when it is open.
void facet_cycle(const Selected& s, const Index* ring, const std::vector<Index>& cell_vertex, const RayVertices& rays,
                 std::vector<Index>& cycle) {
  cycle.clear();
  if (s.open) cycle.push_back(rays.of(s.first_ray));
  for (std::uint32_t k = 0; k < s.ring_size; ++k) {
    const Index vtx = cell_vertex[ring[k]];
    if (cycle.empty() || cycle.back() != vtx) cycle.push_back(vtx);
  }
  if (s.open) cycle.push_back(rays.of(s.last_ray));
  while (cycle.size() > 1 && cycle.back() == cycle.front()) cycle.pop_back();
}

/// Adds a facet to its block: its boundary edges, then its fan triangles from the first vertex
/// with their labels and fields (a facet collapsed to a point or a segment: the closure only).
void add_facet(const Selected& s, const std::vector<Index>& cycle, const RayVertices& rays,
               const std::vector<Index>& original, FacetBlock& out) {
  const std::size_t m = cycle.size();
  for (std::size_t k = 0; k < m && m > 1; ++k) {
    const Index a = cycle[k], c = cycle[(k + 1) % m];
    if (m == 2 && k == 1) break;  // a segment: one edge
    if (a != c) out.edges.push_back({std::min(a, c), std::max(a, c), 0, rays.is_ray(a) || rays.is_ray(c)});
  }
  const int number = out.facets++;
  if (m < 3) {  // collapsed to a point or a segment: kept in the closure only
    ++out.degenerate;
    return;
  }
  const double angle = std::asin(std::clamp(std::max(s.scores.sin_angle_p, s.scores.sin_angle_q), 0.0, 1.0));
  const double ratio = std::max(s.scores.ratio_p, s.scores.ratio_q);
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const Index a = cycle[0], b2 = cycle[k], c = cycle[k + 1];
    if (k >= 2 && a != b2)
      out.edges.push_back({std::min(a, b2), std::max(a, b2), 1, rays.is_ray(a) || rays.is_ray(b2)});
    if (a == b2 || b2 == c || a == c) continue;  // a non-consecutive repeat after merging
    out.faces.push_back({a, b2, c});
    out.polygon.push_back(number);
    out.p.push_back(static_cast<int>(original[s.p]));
    out.q.push_back(static_cast<int>(original[s.q]));
    out.conditions.push_back(s.bits);
    out.unbounded.push_back(s.open ? 1 : 0);
    out.angle.push_back(angle);
    out.ratio.push_back(ratio);
  }
}

/// The kept facets, fan-triangulated, in blocks of kept facets (fixed blocks, in order).
std::vector<FacetBlock> triangulate_facets(const Selection& selection, const std::vector<char>& keep,
                                           const std::vector<Index>& cell_vertex, const RayVertices& rays,
                                           const std::vector<Index>& original, bool parallel) {
  std::vector<std::uint32_t> kept_facets;
  for (std::size_t i = 0; i < selection.selected.size(); ++i)
    if (keep[i]) kept_facets.push_back(static_cast<std::uint32_t>(i));
  std::vector<FacetBlock> blocks(services::block_count(kept_facets.size(), kBlock));
  services::for_blocks(kept_facets.size(), kBlock, parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::vector<Index> cycle;
    for (std::size_t j = begin; j < end; ++j) {
      const Selected& s = selection.selected[kept_facets[j]];
      facet_cycle(s, selection.rings.data() + s.ring_begin, cell_vertex, rays, cycle);
      add_facet(s, cycle, rays, original, blocks[b]);
    }
  });
  return blocks;
}

/// The blocks concatenated in order (each emptied): their triangles with the face labels and
/// fields into the complex, facet numbers made global; returns their edges.
std::vector<EdgeRecord> gather_facets(std::vector<FacetBlock>& blocks, MedialComplex& medial, bool parallel,
                                      MedialReport& info) {
  std::vector<std::size_t> face_offset(blocks.size() + 1, 0), edge_offset(blocks.size() + 1, 0);
  std::vector<int> facet_offset(blocks.size() + 1, 0);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    face_offset[b + 1] = face_offset[b] + blocks[b].faces.size();
    edge_offset[b + 1] = edge_offset[b] + blocks[b].edges.size();
    facet_offset[b + 1] = facet_offset[b] + blocks[b].facets;
    info.degenerate_facets += static_cast<std::size_t>(blocks[b].degenerate);
  }
  info.facets = static_cast<std::size_t>(facet_offset.back());
  // The faces first, then their columns at that size (add_face would grow each column per face).
  medial.faces.resize(face_offset.back());
  auto& polygon = medial.add(kPolygon);
  auto& label_p = medial.add(kDualP);
  auto& label_q = medial.add(kDualQ);
  auto& label_conditions = medial.add(kConditions);
  auto& label_unbounded = medial.add(kUnbounded);
  auto& field_angle = medial.add(kAngle);
  auto& field_ratio = medial.add(kRatio);
  std::vector<EdgeRecord> edges(edge_offset.back());
  const auto gather = [&](std::size_t b) {
    FacetBlock& block = blocks[b];
    const auto at = static_cast<std::ptrdiff_t>(face_offset[b]);
    std::copy(block.faces.begin(), block.faces.end(), medial.faces.begin() + at);
    std::transform(block.polygon.begin(), block.polygon.end(), polygon.begin() + at,
                   [&](int local) { return facet_offset[b] + local; });
    std::copy(block.p.begin(), block.p.end(), label_p.begin() + at);
    std::copy(block.q.begin(), block.q.end(), label_q.begin() + at);
    std::copy(block.conditions.begin(), block.conditions.end(), label_conditions.begin() + at);
    std::copy(block.unbounded.begin(), block.unbounded.end(), label_unbounded.begin() + at);
    std::copy(block.angle.begin(), block.angle.end(), field_angle.begin() + at);
    std::copy(block.ratio.begin(), block.ratio.end(), field_ratio.begin() + at);
    std::copy(block.edges.begin(), block.edges.end(), edges.begin() + static_cast<std::ptrdiff_t>(edge_offset[b]));
    block = FacetBlock{};
  };
  if (parallel) tbb::parallel_for(std::size_t{0}, blocks.size(), gather);
  else for (std::size_t b = 0; b < blocks.size(); ++b) gather(b);
  return edges;
}

/// Sorted by (a, b), each edge once (a Voronoi edge bounds up to three selected facets): a
/// counting sort by a, then each (short) bucket sorted and deduplicated.
std::vector<EdgeRecord> sort_unique_edges(const std::vector<EdgeRecord>& edges, std::size_t nv, bool parallel) {
  std::vector<std::size_t> start(nv + 1, 0);
  for (const EdgeRecord& e : edges) ++start[e.a + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<EdgeRecord> bucketed(edges.size());
  {
    std::vector<std::size_t> cursor(start.begin(), start.end() - 1);
    for (const EdgeRecord& e : edges) bucketed[cursor[e.a]++] = e;
  }
  std::vector<std::uint32_t> kept(nv, 0);
  const auto sort_bucket = [&](std::size_t v) {
    const auto first = bucketed.begin() + static_cast<std::ptrdiff_t>(start[v]);
    const auto last = bucketed.begin() + static_cast<std::ptrdiff_t>(start[v + 1]);
    std::sort(first, last);
    kept[v] = static_cast<std::uint32_t>(
        std::unique(first, last, [](const EdgeRecord& x, const EdgeRecord& y) { return x.b == y.b; }) - first);
  };
  if (parallel) tbb::parallel_for(std::size_t{0}, nv, sort_bucket);
  else for (std::size_t v = 0; v < nv; ++v) sort_bucket(v);
  std::vector<EdgeRecord> out;
  out.reserve(edges.size());
  for (std::size_t v = 0; v < nv; ++v)
    out.insert(out.end(), bucketed.begin() + static_cast<std::ptrdiff_t>(start[v]),
               bucketed.begin() + static_cast<std::ptrdiff_t>(start[v] + kept[v]));
  return out;
}

/// The closure's edges with their labels `fan_diagonal` and, when clipping, `clipped`. The edges
/// first, then their columns at that size (add_edge would grow each column per edge).
void add_edges(MedialComplex& medial, const std::vector<EdgeRecord>& edges, bool clip) {
  medial.edges.reserve(edges.size());
  for (const EdgeRecord& e : edges) medial.edges.push_back({e.a, e.b});
  auto& fan_diagonal = medial.add(kFanDiagonal);
  for (std::size_t i = 0; i < edges.size(); ++i) fan_diagonal[i] = edges[i].diagonal;
  if (!clip) return;
  auto& clipped = medial.add(kClipped);
  for (std::size_t i = 0; i < edges.size(); ++i) clipped[i] = edges[i].clipped;
}

/// The output complex from the kept facets.
MedialComplex build_complex(const Renumbered& points, const DelaunayTetrahedralization& dt, const Selection& selection,
                            const std::vector<char>& keep, const MedialOptions& options, MedialReport& info) {
  const double diagonal = bbox_diagonal(points.P, dt);
  std::optional<UnionFind> classes = merge_close_cells(selection, keep, dt, options.merge_tolerance * diagonal);
  const CellVertices cells = number_cells(selection, keep, dt.cells.size(), classes, info);
  MedialComplex medial;
  medial.generator_kind = options.generator_kind;
  add_cell_vertices(medial, cells, dt, points.original, options.parallel);
  const RayVertices rays = add_ray_vertices(medial, selection, keep, dt, points, options.clip_factor * diagonal);
  std::vector<FacetBlock> blocks = triangulate_facets(selection, keep, cells.of_cell, rays, points.original,
                                                      options.parallel);
  const std::vector<EdgeRecord> edges = gather_facets(blocks, medial, options.parallel, info);
  add_edges(medial, sort_unique_edges(edges, medial.num_vertices(), options.parallel),
            options.unbounded == Unbounded::Clip);
  return medial;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

MedialComplex medial_axis(const MedialInput& input, const MedialOptions& options, MedialReport* report) {
  if (!input.points) throw std::invalid_argument("no points");
  MedialReport info;
  auto t0 = Clock::now();
  const Renumbered points = renumber_points(input, options.parallel);
  InnerSetup inner = plan_inner(input, points, options.inner);

  // A. The Delaunay tetrahedralization (the inner test's setup alongside).
  const DelaunayTetrahedralization dt = tetrahedralize(points, input, options.parallel, inner, info);
  info.seconds_delaunay = seconds_since(t0);

  // B–C. Poles and umbrellas.
  t0 = Clock::now();
  const Umbrellas u = compute_umbrellas(points.P, dt, false, options.parallel);
  count_umbrellas(dt, u, info);
  info.seconds_umbrellas = seconds_since(t0);

  // D–E. The conditions on every edge; rings of the selected.
  t0 = Clock::now();
  const Selection selection = select_edges(points, dt, u, options, info);
  info.seconds_filter = seconds_since(t0);

  // F. Inner/outer selection.
  t0 = Clock::now();
  const std::vector<char> keep = select_inner(points, input, dt, selection, inner, options.parallel, info);
  info.seconds_inner = seconds_since(t0);

  // The output complex.
  t0 = Clock::now();
  MedialComplex medial = build_complex(points, dt, selection, keep, options, info);
  info.seconds_complex = seconds_since(t0);
  if (report) *report = info;
  return medial;
}

}  // namespace medax::dey_zhao
