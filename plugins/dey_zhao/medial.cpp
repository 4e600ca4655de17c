#include "medial.hpp"

#include "inner.hpp"

#include <medax/services/blocks.hpp>
#include <medax/services/delaunay_rings.hpp>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
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

Umbrellas compute_umbrellas(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt, bool keep_triangles,
                            bool parallel) {
  const std::size_t n = dt.cells.size(), np = P.size();
  const auto& cc = dt.circumcentres;
  Umbrellas u;

  // B. Pole: the farthest Voronoi vertex of V_p (ties: the lowest cell). On the hull, V_p is
  // unbounded: v_p is the normalised sum of the unit outward normals of the hull facets at p,
  // the directions of V_p's infinite edges.
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

  // C. Umbrella of p: the Delaunay triangles at p whose dual Voronoi edge crosses the plane
  // through p normal to v_p. sgn'(x) = (x >= 0 ? + : −) is an infinitesimally shifted plane.
  // Each facet is visited once, from its lower cell (or its only finite cell on the hull).
  auto count = std::make_unique<std::atomic<std::uint32_t>[]>(np);
  auto max_r = std::make_unique<std::atomic<std::uint64_t>[]>(np);
  std::vector<std::uint16_t> mask(n, 0);  // bit 3k + m: facet k is in the umbrella of its m-th corner
  const auto& v = u.pole_vector;
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
            count[f[m]].fetch_add(1, std::memory_order_relaxed);
            atomic_max(max_r[f[m]], r);
          }
      }
      mask[c] = bits;
    }
  });
  u.offsets.assign(np + 1, 0);
  u.max_radius.resize(np);
  for (std::size_t x = 0; x < np; ++x) {
    u.offsets[x + 1] = u.offsets[x] + count[x].load(std::memory_order_relaxed);
    const std::uint64_t bits = max_r[x].load(std::memory_order_relaxed);
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

/// `original[i]`: the caller's index of point i; p and q of an edge are ordered by it.
void select_block(const std::vector<Vec3>& P, const std::vector<Index>& original, const DelaunayTetrahedralization& dt,
                  const Umbrellas& u, const MedialOptions& options, std::size_t begin, std::size_t end,
                  SelectionBlock& out) {
  std::vector<Index> forward, backward;
  const double sin_theta = std::sin(options.theta);
  const auto corners = [&](Index c) -> const std::array<Index, 4>& { return dt.cells[c]; };
  const auto neighbour = [&](Index c, int k) {
    const std::int64_t nb = dt.neighbours[c][k];
    return nb == kInf ? kNone : static_cast<Index>(nb);
  };
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
      // Orientation: the cells are positively oriented, so crossing first the facet opposite a
      // (cell_edge_sign > 0) or b walks counter-clockwise about u → w.
      const Index a = corner[e[2]], b = corner[e[3]];
      const bool ccw = services::cell_edge_sign(edge) > 0;
      const Index cross = ccw ? a : b, keep = ccw ? b : a;
      // c owns the edge when it is the lowest cell of the ring (or of the chain between two hull
      // facets, walked both ways).
      forward.assign(1, c);
      Index end_cell = kNone;
      int end_facet = 0;
      std::int64_t last_ray = -1, first_ray = -1;
      const services::RingEnd closed = services::walk_edge_ring(c, uu, ww, cross, keep, corners, neighbour, kNone,
                                                                forward, ~std::size_t{0}, &end_cell, &end_facet);
      if (closed == services::RingEnd::Lower) continue;
      backward.clear();
      if (closed == services::RingEnd::Boundary) {
        last_ray = static_cast<std::int64_t>(end_cell) * 4 + end_facet;
        if (services::walk_edge_ring(c, uu, ww, keep, cross, corners, neighbour, kNone, backward, ~std::size_t{0},
                                     &end_cell, &end_facet) != services::RingEnd::Boundary)
          continue;
        first_ray = static_cast<std::int64_t>(end_cell) * 4 + end_facet;
      }
      // c owns the edge: it is selected. Its scores (fields) and condition bits (label).
      const EdgeScores scores = score_edge(P, u, p, q);
      const int bits = condition_bits(scores, options, sin_theta);
      if (!bits) continue;  // never: passes_any() makes the same tests
      if (bits & (kAngleP | kAngleQ)) ++out.angle;
      if (bits & (kRatioP | kRatioQ)) ++out.ratio;
      const bool open = closed == services::RingEnd::Boundary;
      if (open) {
        ++out.unbounded;
        if (options.unbounded == Unbounded::Drop) {
          ++out.dropped;
          continue;
        }
      }
      Selected s{p, q, scores, bits, open, static_cast<std::uint32_t>(out.rings.size()), 0, first_ray, last_ray};
      // The ring counter-clockwise about u → w: backward reversed, c, forward.
      out.rings.insert(out.rings.end(), backward.rbegin(), backward.rend());
      out.rings.insert(out.rings.end(), forward.begin(), forward.end());
      s.ring_size = static_cast<std::uint32_t>(out.rings.size() - s.ring_begin);
      if (uu != p) {  // orient along p → q instead
        auto first = out.rings.begin() + s.ring_begin, last = out.rings.end();
        if (open) {
          std::reverse(first, last);
          std::swap(s.first_ray, s.last_ray);
        } else {
          std::reverse(first + 1, last);  // keep the owner first
        }
      }
      out.selected.push_back(s);
    }
  }
}

struct UnionFind {
  std::vector<Index> parent;
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a), b = find(b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
  }
};

}  // namespace

// ---------------------------------------------------------------------------------------------

MedialComplex medial_axis(const MedialInput& input, const MedialOptions& options, MedialReport* report) {
  if (!input.points) throw std::invalid_argument("no points");
  MedialReport info;
  auto t0 = Clock::now();
  // Everything below runs on the points renumbered along a space-filling curve (locality);
  // `original` maps back to the caller's indices for the output.
  const std::vector<Index> original = spatial_order(*input.points, options.parallel);
  std::vector<Vec3> P(original.size());
  for (std::size_t i = 0; i < P.size(); ++i) P[i] = (*input.points)[original[i]];

  // Which inner selection can run, and its setup (overlapping the Delaunay tetrahedralization).
  InnerSelection inner = options.inner;
  const bool has_mesh = input.mesh && !input.mesh->faces.empty();
  const bool has_normals = input.normals && input.normals->size() == P.size();
  std::vector<Vec3> normals;
  if (has_normals) {
    normals.resize(P.size());
    for (std::size_t i = 0; i < P.size(); ++i) normals[i] = (*input.normals)[original[i]];
  }
  if (inner == InnerSelection::DelaunaySurface && !(has_mesh && input.points_are_mesh_vertices))
    throw std::invalid_argument("inner selection `delaunay_surface` needs the mesh, with the points being its "
                                "vertices (`points: vertices`)");
  if (inner == InnerSelection::Mesh && !has_mesh)
    throw std::invalid_argument("inner selection `mesh` needs a surface mesh");
  if (inner == InnerSelection::Normals && !has_normals)
    throw std::invalid_argument("inner selection `normals` needs one outward normal per point");
  std::optional<MeshEdgeSide> mesh_side;
  std::string mesh_side_error;
  const bool try_surface = (inner == InnerSelection::Auto || inner == InnerSelection::DelaunaySurface) && has_mesh &&
                           input.points_are_mesh_vertices;
  const bool prepare_mesh = inner == InnerSelection::Mesh || (inner == InnerSelection::Auto && has_mesh && !try_surface);
  const auto setup = [&] {
    if (!prepare_mesh) return;
    try {
      mesh_side.emplace(*input.mesh);
    } catch (const std::invalid_argument& e) {
      if (inner == InnerSelection::Mesh) throw;
      mesh_side_error = e.what();
    }
  };

  // A. The Delaunay tetrahedralization and its circumcentres.
  const DelaunayTetrahedralization dt = services::delaunay_tetrahedralize_alongside(P, {options.parallel}, setup);
  const std::size_t n = dt.cells.size();
  if (n >= kNone / 4) throw std::invalid_argument("too many Delaunay cells for 32-bit indices");
  info.points = dt.vertex_point.size();
  info.cells = n;
  info.seconds_delaunay = seconds_since(t0);

  // B–C. Poles and umbrellas.
  t0 = Clock::now();
  const Umbrellas u = compute_umbrellas(P, dt, false, options.parallel);
  std::size_t hull_facets = 0;
  for (const auto& nb : dt.neighbours)
    for (std::int64_t x : nb) hull_facets += x == kInf;
  for (Index x : dt.vertex_point) {
    info.hull_points += u.on_hull[x] != 0;
    info.empty_umbrellas += u.size(x) == 0;
  }
  // Euler: V − E + F − C = 1 for a triangulated ball, with F = (4C + H) / 2.
  info.delaunay_edges = info.points + (4 * n + hull_facets) / 2 - n - 1;
  info.seconds_umbrellas = seconds_since(t0);

  // D–E. The conditions on every edge, from the lowest cell of its ring; rings of the selected.
  t0 = Clock::now();
  std::vector<SelectionBlock> blocks(services::block_count(n, kBlock));
  services::for_blocks(n, kBlock, options.parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    select_block(P, original, dt, u, options, begin, end, blocks[b]);
  });
  std::vector<Selected> selected;
  std::vector<Index> rings;
  {
    std::size_t count = 0, ring_total = 0;
    for (const auto& b : blocks) count += b.selected.size(), ring_total += b.rings.size();
    selected.reserve(count);
    rings.reserve(ring_total);
    for (auto& b : blocks) {
      const auto shift = static_cast<std::uint32_t>(rings.size());
      for (Selected s : b.selected) {
        s.ring_begin += shift;
        selected.push_back(s);
      }
      rings.insert(rings.end(), b.rings.begin(), b.rings.end());
      info.selected_angle += b.angle;
      info.selected_ratio += b.ratio;
      info.unbounded += b.unbounded;
      info.unbounded_dropped += b.dropped;
      info.selected += b.selected.size() + b.dropped;
      b = SelectionBlock{};
    }
  }
  info.seconds_filter = seconds_since(t0);

  // F. Inner/outer selection.
  t0 = Clock::now();
  std::vector<char> keep(selected.size(), 1);
  std::vector<char> cell_inside;
  if (try_surface) {
    std::size_t missing = 0;
    bool labelled = false;
    try {
      SurfaceMesh renumbered;  // the mesh triangles in the renumbered point indices
      std::vector<Index> position(P.size());
      for (std::size_t i = 0; i < P.size(); ++i) position[original[i]] = static_cast<Index>(i);
      renumbered.faces.reserve(input.mesh->faces.size());
      for (const Tri& f : input.mesh->faces)
        renumbered.faces.push_back({f[0] < P.size() ? position[f[0]] : f[0], f[1] < P.size() ? position[f[1]] : f[1],
                                    f[2] < P.size() ? position[f[2]] : f[2]});
      labelled = label_cells_by_surface(dt, renumbered, cell_inside, missing);
    } catch (const std::invalid_argument&) {
      if (inner == InnerSelection::DelaunaySurface) throw;
      info.inner_note = "the mesh triangles are Delaunay facets but their inside parity is inconsistent; ";
    }
    if (labelled) {
      inner = InnerSelection::DelaunaySurface;
      info.inner_note += "every mesh triangle is a Delaunay facet";
    } else if (inner == InnerSelection::DelaunaySurface) {
      throw std::invalid_argument("inner selection `delaunay_surface`: " + std::to_string(missing) + " of " +
                                  std::to_string(input.mesh->faces.size()) +
                                  " mesh triangles are not Delaunay facets of the points; use `inner: mesh`");
    } else {
      if (!labelled && missing)
        info.inner_note += std::to_string(missing) + " mesh triangles are not Delaunay facets; ";
      try {
        mesh_side.emplace(*input.mesh);
      } catch (const std::invalid_argument& e) {
        mesh_side_error = e.what();
      }
    }
  }
  if (inner == InnerSelection::Auto) {
    if (mesh_side) {
      inner = InnerSelection::Mesh;
      info.inner_note += "general closed mesh";
    } else if (has_normals) {
      inner = InnerSelection::Normals;
      info.inner_note += (has_mesh ? "mesh unusable (" + mesh_side_error + "); " : std::string()) + "oriented normals";
    } else {
      inner = InnerSelection::None;
      info.inner_note += (has_mesh ? "mesh unusable (" + mesh_side_error + "); " : std::string()) +
                         "no mesh and no normals: inner and outer medial axis";
    }
  }
  info.inner_used = inner;
  switch (inner) {
    case InnerSelection::DelaunaySurface:
      for (std::size_t i = 0; i < selected.size(); ++i) {
        const Selected& s = selected[i];
        bool all = !s.open;
        for (std::uint32_t k = 0; k < s.ring_size && all; ++k) all = cell_inside[rings[s.ring_begin + k]] != 0;
        keep[i] = all;
      }
      break;
    case InnerSelection::Mesh: {
      std::vector<std::array<Index, 2>> edges(selected.size());
      for (std::size_t i = 0; i < selected.size(); ++i) edges[i] = {selected[i].p, selected[i].q};
      keep = mesh_side->inner(P, edges, options.parallel);
      break;
    }
    case InnerSelection::Normals: {
      const auto& N = normals;
      for (std::size_t i = 0; i < selected.size(); ++i) {
        const Selected& s = selected[i];
        const Vec3 d = P[s.q] - P[s.p];
        keep[i] = N[s.p].dot(d) < 0 && N[s.q].dot(d) > 0;
      }
      break;
    }
    default: break;
  }
  for (char k : keep) info.outer += !k;
  info.seconds_inner = seconds_since(t0);

  // The output complex: facets with shared Voronoi vertices, fan-triangulated, and their closure.
  t0 = Clock::now();
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  if (!P.empty())
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = P[dt.vertex_point[0]][a];
  for (Index x : dt.vertex_point)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], P[x][a]), hi[a] = std::max(hi[a], P[x][a]);
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const auto& cc = dt.circumcentres;

  // Facet vertices closer than the tolerance are merged (cospherical points: many cells, one
  // circumcentre); each class is represented by its lowest cell.
  const double tolerance = options.merge_tolerance * diagonal;
  UnionFind classes;
  bool merging = false;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    if (!keep[i]) continue;
    const Selected& s = selected[i];
    const Index* r = rings.data() + s.ring_begin;
    for (std::uint32_t k = 0; k < s.ring_size; ++k) {
      if (s.open && k + 1 == s.ring_size) break;  // no Voronoi edge between the chain's two ends
      const Index a = r[k], b = r[(k + 1) % s.ring_size];
      if (a != b && (cc[a] - cc[b]).norm() <= tolerance) {
        if (!merging) {
          classes.parent.resize(n);
          for (std::size_t c = 0; c < n; ++c) classes.parent[c] = static_cast<Index>(c);
          merging = true;
        }
        classes.unite(a, b);
      }
    }
  }
  const auto representative = [&](Index c) { return merging ? classes.find(c) : c; };

  // Vertex numbering: used cells in cell order, then clipped ray ends by (cell, facet).
  std::vector<Index> cell_vertex(n, kNone);
  std::vector<std::int64_t> rays;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    if (!keep[i]) continue;
    const Selected& s = selected[i];
    for (std::uint32_t k = 0; k < s.ring_size; ++k) cell_vertex[rings[s.ring_begin + k]] = 0;
    if (s.open) rays.push_back(s.first_ray), rays.push_back(s.last_ray);
  }
  if (merging)  // a class's lowest cell is one of its used cells; it stands for the others
    for (std::size_t c = 0; c < n; ++c)
      if (cell_vertex[c] != kNone && classes.find(static_cast<Index>(c)) != c) {
        cell_vertex[c] = kNone;
        ++info.merged_vertices;
      }
  std::sort(rays.begin(), rays.end());
  rays.erase(std::unique(rays.begin(), rays.end()), rays.end());
  MedialComplex medial;
  medial.generator_kind = options.generator_kind;
  Index vertices = 0;
  for (std::size_t c = 0; c < n; ++c)
    if (cell_vertex[c] != kNone) cell_vertex[c] = vertices++;
  medial.centres.resize(vertices);
  medial.radii.resize(vertices);
  medial.generators.resize(vertices);
  services::for_blocks(n, kBlock, options.parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const Index v = cell_vertex[c];
      if (v == kNone) continue;
      medial.centres[v] = cc[c];
      medial.radii[v] = dt.circumradii[c];
      std::array<Index, 4> g;
      for (int k = 0; k < 4; ++k) g[k] = original[dt.cells[c][k]];
      std::sort(g.begin(), g.end());
      medial.generators[v].assign(g.begin(), g.end());
    }
  });
  const Index first_ray_vertex = static_cast<Index>(medial.centres.size());
  const double ray_length = options.clip_factor * diagonal;
  for (std::int64_t ray : rays) {
    const Index c = static_cast<Index>(ray / 4);
    const int k = static_cast<int>(ray % 4);
    const auto f = facet_corners(dt.cells[c], k);
    const Vec3 end = cc[c] + ray_length * unit(outward_normal(P, dt.cells[c], k));
    medial.centres.push_back(end);
    medial.radii.push_back((end - P[f[0]]).norm());
    std::array<Index, 3> g{original[f[0]], original[f[1]], original[f[2]]};
    std::sort(g.begin(), g.end());
    medial.generators.emplace_back(g.begin(), g.end());
  }
  const auto ray_vertex = [&](std::int64_t ray) {
    return first_ray_vertex + static_cast<Index>(std::lower_bound(rays.begin(), rays.end(), ray) - rays.begin());
  };

  // The facets, fan-triangulated, in blocks of kept facets (fixed blocks, concatenated in order).
  struct EdgeRecord {
    Index a, b;
    int diagonal, clipped;
    bool operator<(const EdgeRecord& o) const {
      return a != o.a ? a < o.a : b != o.b ? b < o.b : diagonal != o.diagonal ? diagonal < o.diagonal : clipped > o.clipped;
    }
  };
  struct FacetBlock {
    std::vector<Tri> faces;
    std::vector<int> polygon, p, q, conditions, unbounded;
    std::vector<double> angle, ratio;
    std::vector<EdgeRecord> edges;
    int facets = 0, degenerate = 0;
  };
  std::vector<std::uint32_t> kept_facets;
  for (std::size_t i = 0; i < selected.size(); ++i)
    if (keep[i]) kept_facets.push_back(static_cast<std::uint32_t>(i));
  std::vector<FacetBlock> facet_blocks(services::block_count(kept_facets.size(), kBlock));
  services::for_blocks(kept_facets.size(), kBlock, options.parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    FacetBlock& out = facet_blocks[b];
    std::vector<Index> cycle;
    const auto is_ray = [&](Index x) { return x >= first_ray_vertex; };
    for (std::size_t j = begin; j < end; ++j) {
      const Selected& s = selected[kept_facets[j]];
      cycle.clear();
      if (s.open) cycle.push_back(ray_vertex(s.first_ray));
      for (std::uint32_t k = 0; k < s.ring_size; ++k) {
        const Index vtx = cell_vertex[representative(rings[s.ring_begin + k])];
        if (cycle.empty() || cycle.back() != vtx) cycle.push_back(vtx);
      }
      if (s.open) cycle.push_back(ray_vertex(s.last_ray));
      while (cycle.size() > 1 && cycle.back() == cycle.front()) cycle.pop_back();
      const std::size_t m = cycle.size();
      for (std::size_t k = 0; k < m && m > 1; ++k) {
        const Index a = cycle[k], c = cycle[(k + 1) % m];
        if (m == 2 && k == 1) break;  // a segment: one edge
        if (a != c) out.edges.push_back({std::min(a, c), std::max(a, c), 0, is_ray(a) || is_ray(c)});
      }
      const int number = out.facets++;
      if (m < 3) {  // collapsed to a point or a segment: kept in the closure only
        ++out.degenerate;
        continue;
      }
      const double angle = std::asin(std::clamp(std::max(s.scores.sin_angle_p, s.scores.sin_angle_q), 0.0, 1.0));
      const double ratio = std::max(s.scores.ratio_p, s.scores.ratio_q);
      for (std::size_t k = 1; k + 1 < m; ++k) {
        const Index a = cycle[0], b2 = cycle[k], c = cycle[k + 1];
        if (k >= 2 && a != b2) out.edges.push_back({std::min(a, b2), std::max(a, b2), 1, is_ray(a) || is_ray(b2)});
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
  });
  std::vector<std::size_t> face_offset(facet_blocks.size() + 1, 0), edge_offset(facet_blocks.size() + 1, 0);
  std::vector<int> facet_offset(facet_blocks.size() + 1, 0);
  for (std::size_t b = 0; b < facet_blocks.size(); ++b) {
    face_offset[b + 1] = face_offset[b] + facet_blocks[b].faces.size();
    edge_offset[b + 1] = edge_offset[b] + facet_blocks[b].edges.size();
    facet_offset[b + 1] = facet_offset[b] + facet_blocks[b].facets;
    info.degenerate_facets += static_cast<std::size_t>(facet_blocks[b].degenerate);
  }
  const std::size_t total_faces = face_offset.back();
  medial.faces.resize(total_faces);
  auto& polygon = medial.face_props.labels.add("polygon", total_faces);
  auto& label_p = medial.face_props.labels.add("p", total_faces);
  auto& label_q = medial.face_props.labels.add("q", total_faces);
  auto& label_conditions = medial.face_props.labels.add("conditions", total_faces);
  auto& label_unbounded = medial.face_props.labels.add("unbounded", total_faces);
  auto& field_angle = medial.face_props.fields.add("angle", total_faces);
  auto& field_ratio = medial.face_props.fields.add("ratio", total_faces);
  std::vector<EdgeRecord> edges(edge_offset.back());
  const auto gather = [&](std::size_t b) {
    FacetBlock& block = facet_blocks[b];
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
  if (options.parallel) tbb::parallel_for(std::size_t{0}, facet_blocks.size(), gather);
  else for (std::size_t b = 0; b < facet_blocks.size(); ++b) gather(b);
  const int facets = facet_offset.back();
  info.facets = static_cast<std::size_t>(facets);
  // Sorted by (a, b), each edge once (a Voronoi edge bounds up to three selected facets): a
  // counting sort by a, then each (short) bucket sorted and deduplicated.
  {
    const std::size_t nv = medial.centres.size();
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
    if (options.parallel) tbb::parallel_for(std::size_t{0}, nv, sort_bucket);
    else for (std::size_t v = 0; v < nv; ++v) sort_bucket(v);
    edges.clear();
    for (std::size_t v = 0; v < nv; ++v)
      edges.insert(edges.end(), bucketed.begin() + static_cast<std::ptrdiff_t>(start[v]),
                   bucketed.begin() + static_cast<std::ptrdiff_t>(start[v] + kept[v]));
  }
  medial.edges.reserve(edges.size());
  auto& diagonal_label = medial.edge_props.labels.add("fan_diagonal", 0);
  diagonal_label.reserve(edges.size());
  for (const EdgeRecord& e : edges) {
    medial.edges.push_back({e.a, e.b});
    diagonal_label.push_back(e.diagonal);
  }
  if (options.unbounded == Unbounded::Clip) {
    auto& clipped = medial.edge_props.labels.add("clipped", 0);
    for (const EdgeRecord& e : edges) clipped.push_back(e.clipped);
  }
  info.seconds_complex = seconds_since(t0);
  if (report) *report = info;
  return medial;
}

}  // namespace medax::dey_zhao
