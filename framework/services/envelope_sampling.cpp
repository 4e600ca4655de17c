// Points on the boundary of the envelope (Envelope::sample_boundary): a narrow band of grid
// cells around ∂E by octree refinement, the sign of φ at their grid points coarse to fine, and
// one point per grid edge whose ends lie on opposite sides of ∂E, weighted by the area it
// stands for.
#include "envelope_sampling.hpp"

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace medax::services {

double EnvelopeSamples::total_area() const { return std::accumulate(areas.begin(), areas.end(), 0.0); }

namespace envelope_detail {

namespace {

constexpr int kLastLevel = 2;  // octree cells of 4×4×4 steps, then grid points (2 measured best)

// A grid point (i, j, k) packed into one sortable key.
constexpr int kKeyBits = 21;
constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << kKeyBits) - 1;
inline std::uint64_t pack(std::uint64_t i, std::uint64_t j, std::uint64_t k) {
  return (i << (2 * kKeyBits)) | (j << kKeyBits) | k;
}
inline std::array<std::uint64_t, 3> unpack(std::uint64_t key) {
  return {key >> (2 * kKeyBits), (key >> kKeyBits) & kKeyMask, key & kKeyMask};
}

/// The finest lattice L_p (coordinates multiples of 2^p, p ≤ kLastLevel) a grid point is on.
int lattice_of(std::uint64_t key) {
  const auto [i, j, k] = unpack(key);
  const std::uint64_t bits = i | j | k;
  int p = 0;
  while (p < kLastLevel && !((bits >> p) & 1)) ++p;
  return p;
}

/// A fixed, generic rotation (no axis close to a coordinate axis or plane).
Eigen::Matrix3d grid_rotation() {
  return Eigen::AngleAxisd(0.9, Vec3(1.0, std::sqrt(2.0), std::sqrt(3.0)).normalized()).toRotationMatrix();
}

/// An octree cell: its lowest grid point and a primitive to try first.
struct Cell {
  std::uint32_t i, j, k;
  std::int64_t hint;  ///< a primitive near the parent cell's centre, −1 if none
};

/// Grid points whose value settles their sign, from the octree refinement (sorted by key).
using KnownValues = std::vector<std::pair<std::uint64_t, Hit>>;
/// A grid edge crossing ∂E: the indices (into the corner keys) of its outside and inside end.
using Crossing = std::array<std::uint64_t, 2>;

/// The sampling grid. It is turned by a fixed generic rotation: a grid aligned with the
/// coordinate axes would alias with axis-aligned shapes (every cross-section of an axis-aligned
/// cylinder meets the grid lines the same way, so the area estimate's errors add up instead of
/// averaging).
struct Grid {
  Eigen::Matrix3d rotation;  // grid frame -> world
  Vec3 origin;               // in the grid frame
  double step = 0;
  int levels = 0;            // the root cell has 2^levels steps a side
  double scale = 0;          // the grid's diagonal
  double slack = 0;          // rounding in φ, which is 1-Lipschitz in exact arithmetic

  Grid(const EnvelopeBvh& bvh, double step_) : rotation(grid_rotation()), step(step_) {
    Box bounds;
    for (const PrimGeom& g : bvh.geometry())
      for (int k = 0; k < g.count; ++k) {
        const Vec3 c = rotation.transpose() * g.c[k];
        bounds.add(Vec3(c.array() - g.r[k]));
        bounds.add(Vec3(c.array() + g.r[k]));
      }
    origin = bounds.lo - Vec3::Constant(step);
    const Vec3 extent = bounds.hi - bounds.lo + Vec3::Constant(2 * step);
    const double cells_max = std::ceil(extent.maxCoeff() / step);
    if (cells_max >= static_cast<double>(std::uint64_t{1} << (kKeyBits - 1)))
      throw std::invalid_argument("envelope sampling: the step " + std::to_string(step) +
                                  " is too small for an envelope of size " + std::to_string(extent.maxCoeff()));
    while (static_cast<double>(std::uint64_t{1} << levels) < cells_max) ++levels;
    scale = extent.norm();
    slack = 1e-9 * scale;
  }

  Vec3 point(std::uint64_t i, std::uint64_t j, std::uint64_t k) const {
    return Vec3(rotation * (origin + step * Vec3(double(i), double(j), double(k))));
  }
  Vec3 point(std::uint64_t key) const {
    const auto [i, j, k] = unpack(key);
    return point(i, j, k);
  }
};

/// 1. Octree refinement down to cells of 4×4×4 grid steps (level kLastLevel): keep a cell when
///    its centre (a grid point) is within half a diagonal of ∂E, as φ is 1-Lipschitz. The values
///    found that settle a grid point's sign go into `known`, for step 2.
std::vector<Cell> narrow_band(const EnvelopeBvh& bvh, const Grid& grid, KnownValues& known,
                              const std::function<void(double)>& report, const CancelPoll& poll) {
  std::vector<Cell> cells{{0, 0, 0, -1}};
  for (int level = grid.levels; level >= kLastLevel; --level) {
    const std::uint32_t size = std::uint32_t{1} << level, half = size / 2;
    const double half_diagonal = 0.5 * std::sqrt(3.0) * size * grid.step + grid.slack;
    std::vector<Hit> hits(cells.size());
    tbb::parallel_for(std::size_t{0}, cells.size(), [&](std::size_t c) {
      poll.at(c);
      const Cell& cell = cells[c];
      // Only the class matters: φ > h (nothing found below h), φ < −h, or between. The parent's
      // primitive often settles it at once.
      const Vec3 centre = grid.point(cell.i + half, cell.j + half, cell.k + half);
      Hit start{kInf, -1};
      if (cell.hint >= 0) start = {bvh.primitive(cell.hint).value(centre), cell.hint};
      hits[c] = bvh.query(centre, half_diagonal * (1 + 1e-9), -half_diagonal, half_diagonal, start);
    });
    std::vector<Cell> next;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      poll.at(c);
      // Reusable as a corner value: inside (sign), or outside by more than a step (nothing to
      // locate from it). A kept cell's positive value is only an upper bound.
      if (hits[c].d < 0 || hits[c].prim < 0)
        known.push_back({pack(cells[c].i + half, cells[c].j + half, cells[c].k + half), hits[c]});
      if (hits[c].prim < 0 || hits[c].d < -half_diagonal) continue;
      for (std::uint32_t a = 0; a < 8; ++a)
        next.push_back({cells[c].i + ((a & 1) ? half : 0), cells[c].j + ((a & 2) ? half : 0),
                        cells[c].k + ((a & 4) ? half : 0), hits[c].prim});
    }
    cells = std::move(next);
    report(0.4 * (grid.levels - level + 1) / grid.levels);
  }
  std::sort(known.begin(), known.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return cells;
}

/// `keys` sorted, each once: a counting sort on i (the high bits), then each slice of one i
/// sorted on its own, in parallel; a stop is seen between slices.
std::vector<std::uint64_t> sorted_unique(const std::vector<std::uint64_t>& keys, const CancelPoll& poll) {
  const auto slice = [](std::uint64_t key) { return static_cast<std::size_t>(key >> (2 * kKeyBits)); };
  std::size_t slices = 0;
  for (std::uint64_t key : keys) slices = std::max(slices, slice(key) + 1);
  std::vector<std::size_t> start(slices + 1, 0);
  for (std::uint64_t key : keys) ++start[slice(key) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint64_t> sorted(keys.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (std::uint64_t key : keys) sorted[next[slice(key)]++] = key;
  poll.now();
  tbb::parallel_for(std::size_t{0}, slices, [&](std::size_t s) {
    poll.now();
    std::sort(sorted.begin() + start[s], sorted.begin() + start[s + 1]);
  });
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  return sorted;
}

/// The grid points of the narrow band's cells (the children of the last level's cells,
/// 2^(kLastLevel−1) steps a side, corners included), sorted, each once: the corners of the unit
/// cells inside them. Generated per band cell rather than per unit cell, which gives 27 keys
/// instead of 64 per band cell to sort.
std::vector<std::uint64_t> corner_keys(const std::vector<Cell>& cells, const CancelPoll& poll) {
  constexpr std::uint32_t side = (std::uint32_t{1} << (kLastLevel - 1)) + 1;  // grid points per side
  constexpr std::size_t per_cell = side * side * side;
  std::vector<std::uint64_t> corners(per_cell * cells.size());
  tbb::parallel_for(std::size_t{0}, cells.size(), [&](std::size_t c) {
    poll.at(c);
    std::uint64_t* out = corners.data() + per_cell * c;
    for (std::uint32_t a = 0; a < side; ++a)
      for (std::uint32_t b = 0; b < side; ++b)
        for (std::uint32_t d = 0; d < side; ++d) *out++ = pack(cells[c].i + a, cells[c].j + b, cells[c].k + d);
  });
  return sorted_unique(corners, poll);
}

/// Where each grid point is among the sorted corner keys: an open-addressing hash of the keys (a
/// lookup costs a hash and a probe or two instead of a binary search over every corner).
class CornerIndex {
 public:
  explicit CornerIndex(const std::vector<std::uint64_t>& corners) : corners_(corners) {
    int bits = 4;
    while ((std::size_t{1} << bits) < 2 * corners.size()) ++bits;
    shift_ = 64 - bits;
    slots_.assign(std::size_t{1} << bits, kEmpty);
    for (std::size_t c = 0; c < corners.size(); ++c) {
      std::size_t slot = home(corners[c]);
      while (slots_[slot] != kEmpty) slot = (slot + 1) & (slots_.size() - 1);
      slots_[slot] = static_cast<std::uint32_t>(c);
    }
  }
  const std::vector<std::uint64_t>& keys() const { return corners_; }
  /// The index of grid point `key` among the corners, or corners.size() when it is not one.
  std::size_t find(std::uint64_t key) const {
    for (std::size_t slot = home(key);; slot = (slot + 1) & (slots_.size() - 1)) {
      const std::uint32_t c = slots_[slot];
      if (c == kEmpty) return corners_.size();
      if (corners_[c] == key) return c;
    }
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ull) >> shift_);
  }
  const std::vector<std::uint64_t>& corners_;
  std::vector<std::uint32_t> slots_;
  int shift_ = 60;
};

/// The value at grid point z (key) of pass p < kLastLevel, from its neighbours on L_{p+1}, whose
/// values are known: a neighbour far enough settles it by the Lipschitz bound (primitive −1,
/// `settled`); otherwise the best of their primitives at z seeds the search (stopping at one that
/// contains z, which settles the sign). `outside` receives the best lower bound on φ(z) the
/// neighbours give (a value ≥ 0 of a neighbour is exact or a lower bound; φ is 1-Lipschitz).
Hit from_parents(const EnvelopeBvh& bvh, const CornerIndex& corners, const std::vector<Hit>& values,
                 std::uint64_t key, const Vec3& z, double step, int pass, double pass_reach, bool& settled,
                 double& outside) {
  const auto [i, j, k] = unpack(key);
  // Parents: round each coordinate off L_{pass+1} down or up.
  const std::uint64_t s = std::uint64_t{1} << pass, m = 2 * s;
  const bool oi = i % m, oj = j % m, ok = k % m;
  const double offset = s * step * std::sqrt(double(oi + oj + ok));
  Hit start{kInf, -1};
  std::int64_t tried[8];
  int ntried = 0;
  for (std::uint32_t a = 0; a < 8; ++a) {
    if (((a & 1) && !oi) || ((a & 2) && !oj) || ((a & 4) && !ok)) continue;
    const std::uint64_t parent = pack(oi ? i - s + ((a & 1) ? m : 0) : i, oj ? j - s + ((a & 2) ? m : 0) : j,
                                      ok ? k - s + ((a & 4) ? m : 0) : k);
    const std::size_t at = corners.find(parent);
    if (at == values.size()) continue;
    const Hit& near = values[at];
    if (near.d >= pass_reach + offset) {  // 1-Lipschitz: φ(z) ≥ φ(near) − offset ≥ reach
      settled = true;
      return Hit{near.d - offset, -1};
    }
    if (near.d >= 0) outside = std::max(outside, near.d - offset);
    const std::int64_t prim = near.prim;
    if (prim < 0 || std::find(tried, tried + ntried, prim) != tried + ntried) continue;
    tried[ntried++] = prim;
    const double d = bvh.primitive(prim).value(z);
    if (d < start.d) start = {d, prim};
    if (d < 0) break;
  }
  return start;
}

/// How far the last pass's searches look: one step (an outside end of a crossing edge is within
/// a step of E).
double last_pass_reach(const Grid& grid) { return grid.step * (1 + 1e-9) + grid.slack; }

/// The primitive of a last-pass value that only bounds φ from below (outside by the neighbours'
/// values), not searched.
constexpr std::int64_t kUnsearched = -2;

/// 2. φ at the grid points `corners`. Only what a crossing edge needs is computed: the sign, and
///    for an outside point next to a crossing (so within one step of E) the exact value and
///    primitive. A search stops at the first primitive containing the point and ignores anything
///    farther than its reach.
///    Coarse-to-fine passes over the lattices L_p (coordinates multiples of 2^p): pass p takes
///    the points of L_p not in L_{p+1}. Their values are exact up to a reach large enough for a
///    far value to settle (1-Lipschitz) the points of the next pass around it without a search.
///    A point of a later pass also tries the primitives found at its neighbours on L_{p+1}: one
///    that contains it settles its sign, and the smallest value seeds the search. A point of the
///    last pass that a neighbour's value proves outside is not searched here (kUnsearched).
std::vector<Hit> corner_values(const EnvelopeBvh& bvh, const Grid& grid, const CornerIndex& index,
                               const KnownValues& known, const CancelPoll& poll) {
  const std::vector<std::uint64_t>& corners = index.keys();
  std::vector<Hit> values(corners.size());
  const double step = grid.step;
  for (int pass = kLastLevel; pass >= 0; --pass) {
    const double stride = double(std::uint64_t{1} << pass);
    const double pass_reach =
        pass == 0 ? last_pass_reach(grid) : (step + 0.5 * stride * std::sqrt(3.0) * step) * (1 + 1e-9) + grid.slack;
    tbb::parallel_for(std::size_t{0}, corners.size(), [&](std::size_t c) {
      poll.at(c);
      if (lattice_of(corners[c]) != pass) return;
      const auto it = std::lower_bound(known.begin(), known.end(), corners[c],
                                       [](const auto& entry, std::uint64_t key) { return entry.first < key; });
      if (it != known.end() && it->first == corners[c]) {
        values[c] = it->second;
        return;
      }
      const Vec3 z = grid.point(corners[c]);
      Hit start{kInf, -1};
      if (pass < kLastLevel) {
        bool settled = false;
        double outside = -kInf;
        start = from_parents(bvh, index, values, corners[c], z, step, pass, pass_reach, settled, outside);
        if (settled) {
          values[c] = start;
          return;
        }
        // Outside by the Lipschitz bound: the last pass needs no more unless the point ends a
        // crossing edge (exact_crossing_ends).
        if (pass == 0 && start.d >= 0 && outside > grid.slack) {
          values[c] = {outside, kUnsearched};
          return;
        }
      }
      values[c] = bvh.query(z, pass_reach, 0.0, -kInf, start);
    });
  }
  return values;
}

/// 3. Every grid edge whose ends differ in sign crosses ∂E. The edges of each corner towards +i,
///    +j, +k are tested in parallel (a bit per axis), then listed in corner and axis order, the
///    order of a sequential scan.
std::vector<Crossing> crossing_edges(const CornerIndex& index, const std::vector<Hit>& values,
                                    const CancelPoll& poll) {
  const std::vector<std::uint64_t>& corners = index.keys();
  const auto neighbour = [&](std::size_t c, int axis) {
    const auto [i, j, k] = unpack(corners[c]);
    return index.find(pack(i + (axis == 0), j + (axis == 1), k + (axis == 2)));
  };
  std::vector<std::uint8_t> crossing_axes(corners.size(), 0);
  tbb::parallel_for(std::size_t{0}, corners.size(), [&](std::size_t c) {
    poll.at(c);
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t n = neighbour(c, axis);
      if (n < corners.size() && (values[c].d >= 0) != (values[n].d >= 0)) crossing_axes[c] |= std::uint8_t(1 << axis);
    }
  });
  std::vector<Crossing> crossings;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    poll.at(c);
    for (int axis = 0; axis < 3; ++axis) {
      if (!(crossing_axes[c] & (1 << axis))) continue;
      const std::size_t n = neighbour(c, axis);
      crossings.push_back(values[c].d >= 0 ? Crossing{c, n} : Crossing{n, c});
    }
  }
  return crossings;
}

/// 3. (cont.) The exact value and primitive at each crossing edge's outside end left unsearched
///    by corner_values: the search it would have made, from the same seed, so the boundary points
///    are those of searching every grid point. Most such points end no crossing edge.
void exact_crossing_ends(const EnvelopeBvh& bvh, const Grid& grid, const CornerIndex& index,
                         const std::vector<Crossing>& crossings, std::vector<Hit>& values, const CancelPoll& poll) {
  const std::vector<std::uint64_t>& corners = index.keys();
  std::vector<std::uint64_t> ends;
  for (const Crossing& e : crossings)
    if (values[e[0]].prim == kUnsearched) ends.push_back(e[0]);
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::vector<Hit> exact(ends.size());
  const double reach = last_pass_reach(grid);
  tbb::parallel_for(std::size_t{0}, ends.size(), [&](std::size_t e) {
    poll.at(e);
    const std::uint64_t key = corners[ends[e]];
    const Vec3 z = grid.point(key);
    bool settled = false;
    double outside = -kInf;
    const Hit start = from_parents(bvh, index, values, key, z, grid.step, 0, reach, settled, outside);
    exact[e] = bvh.query(z, reach, 0.0, -kInf, start);
  });
  for (std::size_t e = 0; e < ends.size(); ++e) values[ends[e]] = exact[e];
}

/// 3. (cont.) A crossing edge's point is the closest point of E to its outside end a (exactly on
///    ∂E: a is outside, so the closest point of the nearest primitive is the closest point of the
///    union), with outward normal (a − c*)/|a − c*|.
/// 4. A plane with unit normal n cuts ‖n‖₁ grid edges per step² of area (n in the grid's
///    frame), so the point stands for step² / ‖n‖₁ of area.
void crossing_points(const EnvelopeBvh& bvh, const Grid& grid, const std::vector<std::uint64_t>& corners,
                     const std::vector<Hit>& values, const std::vector<Crossing>& crossings, EnvelopeSamples& out,
                     const CancelPoll& poll) {
  out.points.resize(crossings.size());
  out.normals.resize(crossings.size());
  out.primitives.resize(crossings.size());
  out.areas.resize(crossings.size());
  tbb::parallel_for(std::size_t{0}, crossings.size(), [&](std::size_t e) {
    poll.at(e);
    const std::size_t a = crossings[e][0], b = crossings[e][1];
    const Vec3 pa = grid.point(corners[a]), pb = grid.point(corners[b]);
    Hit hit = values[a];
    if (hit.prim < 0) hit = bvh.query(pa);  // not expected: an outside end is within a step of E
    const Eval ball = bvh.ball(pa, hit.prim);
    Vec3 n = pa - ball.c;
    const double len = n.norm();
    n = len > 1e-12 * grid.scale ? Vec3(n / len) : Vec3((pa - pb).normalized());
    out.points[e] = hit.d > 0 ? Vec3(ball.c + ball.r * n) : pa;
    out.normals[e] = n;
    out.primitives[e] = bvh.public_index(hit.prim);
    out.areas[e] = grid.step * grid.step / (grid.rotation.transpose() * n).lpNorm<1>();
  });
}

/// A grid point near a point to refine, and the primitive that starts its search.
using SeededKey = std::pair<std::uint64_t, std::int64_t>;

/// The grid points in the shells inner[c] ≤ |z − centres[c]| ≤ outer[c] (clamped to the grid),
/// sorted, each once, with the seed of the first centre that reaches them.
std::vector<SeededKey> keys_near(const Grid& grid, const std::vector<Vec3>& centres, const std::vector<double>& inner,
                                 const std::vector<double>& outer, const std::vector<std::int64_t>& seeds,
                                 const CancelPoll& poll) {
  const double last = double(std::uint64_t{1} << grid.levels);
  std::vector<SeededKey> keys;
  for (std::size_t c = 0; c < centres.size(); ++c) {
    poll.at(c);
    const Vec3 g = (grid.rotation.transpose() * centres[c] - grid.origin) / grid.step;  // grid units
    const double r = outer[c] / grid.step, r0 = std::max(0.0, inner[c] / grid.step);
    Vec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::clamp(std::ceil(g[a] - r), 0.0, last);
      hi[a] = std::clamp(std::floor(g[a] + r), 0.0, last);
    }
    for (double i = lo[0]; i <= hi[0]; ++i)
      for (double j = lo[1]; j <= hi[1]; ++j)
        for (double k = lo[2]; k <= hi[2]; ++k)
          if (const double d2 = (Vec3(i, j, k) - g).squaredNorm(); d2 <= r * r && d2 >= r0 * r0)
            keys.push_back({pack(std::uint64_t(i), std::uint64_t(j), std::uint64_t(k)), seeds[c]});
  }
  poll.now();
  std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  keys.erase(std::unique(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
             keys.end());
  return keys;
}

}  // namespace

std::vector<Vec3> sample_boundary_near(const EnvelopeBvh& bvh, double step, const std::vector<Vec3>& centres,
                                       const std::vector<double>& inner, const std::vector<double>& outer,
                                       const std::vector<std::int64_t>& seeds, const CancelPoll& poll) {
  if (bvh.geometry().empty() || centres.empty()) return {};
  const Grid grid(bvh, step);
  const std::vector<SeededKey> keys = keys_near(grid, centres, inner, outer, seeds, poll);
  std::vector<std::uint64_t> corners(keys.size());
  for (std::size_t c = 0; c < keys.size(); ++c) corners[c] = keys[c].first;
  // Each point searched as the last pass of corner_values does (the sign, and the exact value
  // within a step), from its centre's deepest primitive, which settles most inside points.
  std::vector<Hit> values(corners.size());
  const double reach = last_pass_reach(grid);
  tbb::parallel_for(std::size_t{0}, corners.size(), [&](std::size_t c) {
    poll.at(c);
    const Vec3 z = grid.point(corners[c]);
    const std::int64_t seed = keys[c].second;
    values[c] = bvh.query(z, reach, 0.0, -kInf, Hit{bvh.primitive(seed).value(z), seed});
  });
  EnvelopeSamples out;
  crossing_points(bvh, grid, corners, values, crossing_edges(CornerIndex(corners), values, poll), out, poll);
  return out.points;
}

EnvelopeSamples sample_boundary(const EnvelopeBvh& bvh, double step, const std::function<void(double)>& progress,
                                const CancelPoll& poll) {
  if (!(step > 0) || !std::isfinite(step)) throw std::invalid_argument("envelope sampling: the step must be > 0");
  EnvelopeSamples out;
  out.step = step;
  if (bvh.geometry().empty()) return out;
  const auto report = [&](double f) {
    if (progress) progress(f);
  };
  const Grid grid(bvh, step);
  KnownValues known;
  const std::vector<std::uint64_t> corners = corner_keys(narrow_band(bvh, grid, known, report, poll), poll);
  const CornerIndex index(corners);
  std::vector<Hit> values = corner_values(bvh, grid, index, known, poll);
  report(0.8);
  const std::vector<Crossing> crossings = crossing_edges(index, values, poll);
  exact_crossing_ends(bvh, grid, index, crossings, values, poll);
  report(0.9);
  crossing_points(bvh, grid, corners, values, crossings, out, poll);
  report(1.0);
  return out;
}

}  // namespace envelope_detail

}  // namespace medax::services
