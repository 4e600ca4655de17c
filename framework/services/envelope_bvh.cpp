// Building the envelope's bounding-volume hierarchy (envelope_bvh.hpp): split at the middle of
// the widest of four keys, two primitives per leaf, subtrees built in parallel, and per node the
// centre box, the largest radius and an affine fit of the radii (the node's lower bounds).
#include "envelope_bvh.hpp"

#include <Eigen/Cholesky>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace medax::services::envelope_detail {

namespace {

constexpr std::uint32_t kLeafSize = 2;  // primitives per leaf (2 measured best, 1 as good, 4 and 8 worse)

inline float round_down(double v) {
  const float f = static_cast<float>(v);
  return double(f) <= v ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
inline float round_up(double v) {
  const float f = static_cast<float>(v);
  return double(f) >= v ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

/// Sums over vertex balls (c, r): count, Σc, Σccᵀ, Σr, Σcr.
struct Moments {
  double n = 0, r = 0;
  Vec3 c = Vec3::Zero(), cr = Vec3::Zero();
  Eigen::Matrix3d cc = Eigen::Matrix3d::Zero();
  void add(const Vec3& centre, double radius) {
    n += 1;
    r += radius;
    c += centre;
    cr += radius * centre;
    cc += centre * centre.transpose();
  }
  Moments& operator+=(const Moments& o) {
    n += o.n;
    r += o.r;
    c += o.c;
    cr += o.cr;
    cc += o.cc;
    return *this;
  }
};

/// Per-primitive data for building: split keys, centre box, largest radius, and the moments
/// of its vertex balls (additive, so that a node's radius fit comes from its children's).
struct BuildItem {
  std::array<double, 4> key;  // centre-box midpoint, 2·r_max (ball sizes grouped too)
  std::array<Eigen::Matrix<double, 4, 1, Eigen::DontAlign>, 3> balls;  // (c, r) of its vertices
  int count = 0;
  Box box;
  double rmax = 0;
  Moments moments;
};

BuildItem build_item(const PrimGeom& g) {
  BuildItem item;
  for (int k = 0; k < g.count; ++k) {
    item.balls[k] << g.c[k], g.r[k];
    item.box.add(g.c[k]);
    item.rmax = std::max(item.rmax, g.r[k]);
    item.moments.add(g.c[k], g.r[k]);
  }
  item.count = g.count;
  for (int k = 0; k < 3; ++k) item.key[k] = 0.5 * (item.box.lo[k] + item.box.hi[k]);
  item.key[3] = 2.0 * item.rmax;
  return item;
}

void set_bounds(BvhNode& node, const Box& box, double radius) {
  for (int k = 0; k < 3; ++k) {
    node.lo[k] = round_down(box.lo[k]);
    node.hi[k] = round_up(box.hi[k]);
  }
  node.rmax = round_up(radius);
}

/// Least-squares slope g of r ≈ r̄ + g·(c − c̄) over the balls the moments describe, capped
/// below 1 and rounded to what the node stores; sets node.g and node.slope, returns g.
Vec3 fit_slope(BvhNode& node, const Moments& m) {
  Vec3 g = Vec3::Zero();
  if (m.n > 1) {
    const Vec3 mean = m.c / m.n;
    Eigen::Matrix3d a = m.cc / m.n - mean * mean.transpose();
    const Vec3 b = m.cr / m.n - mean * (m.r / m.n);
    a += (1e-12 * (a.trace() + 1e-300)) * Eigen::Matrix3d::Identity();
    g = a.ldlt().solve(b);
    if (!g.allFinite()) g = Vec3::Zero();
    const double slope = g.norm();
    constexpr double kMaxSlope = 0.95;
    if (slope > kMaxSlope) g *= kMaxSlope / slope;
  }
  for (int k = 0; k < 3; ++k) {
    node.g[k] = static_cast<float>(g[k]);
    g[k] = double(node.g[k]);  // the bound is exact for whatever g is stored
  }
  node.slope = round_up(g.norm());
  return g;
}

/// Builds the nodes over `items`, reordering `order` (primitive indices) into BVH order.
class Builder {
 public:
  Builder(std::vector<BvhNode>& nodes, std::vector<Index>& order, const std::vector<BuildItem>& items)
      : nodes_(nodes), order_(order), items_(items) {}

  /// Builds the subtree of primitives order[begin, end) at node `id`; a subtree of n primitives
  /// owns the 2n − 1 node slots from `id` (left child at id + 1, right child after the left
  /// subtree's slots), so that subtrees can be built in parallel. Returns the subtree's moments.
  Moments build(std::uint32_t id, std::uint32_t begin, std::uint32_t end) {
    if (end - begin <= kLeafSize) return build_leaf(id, begin, end);
    const std::uint32_t mid = split(begin, end);
    const std::uint32_t left = id + 1, right = id + 2 * (mid - begin);
    Moments ml, mr;
    if (end - begin > 8192) {
      tbb::parallel_invoke([&] { ml = build(left, begin, mid); }, [&] { mr = build(right, mid, end); });
    } else {
      ml = build(left, begin, mid);
      mr = build(right, mid, end);
    }
    BvhNode& node = nodes_[id];
    const BvhNode& a = nodes_[left];
    const BvhNode& b = nodes_[right];
    Box box;
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min(a.lo[k], b.lo[k]);
      box.hi[k] = std::max(a.hi[k], b.hi[k]);
    }
    set_bounds(node, box, std::max(double(a.rmax), double(b.rmax)));
    Moments m = ml;
    m += mr;
    const Vec3 g = fit_slope(node, m);
    node.gamma = round_down(-max_offset(g, begin, end));
    node.first = right;
    node.count = 0;
    return m;
  }

 private:
  Moments build_leaf(std::uint32_t id, std::uint32_t begin, std::uint32_t end) {
    BvhNode& node = nodes_[id];
    Box box;
    double radius = 0;
    Moments m;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.add(items_[order_[i]].box);
      radius = std::max(radius, items_[order_[i]].rmax);
      m += items_[order_[i]].moments;
    }
    set_bounds(node, box, radius);
    const Vec3 g = fit_slope(node, m);
    node.gamma = round_down(-max_offset(g, begin, end));
    node.first = begin;
    node.count = end - begin;
    return m;
  }

  /// Splits order[begin, end) along the widest of the four keys, at the middle of its range
  /// (object median when that leaves a side empty); returns the first index of the right side.
  std::uint32_t split(std::uint32_t begin, std::uint32_t end) {
    double lo4[4], hi4[4];
    for (int a = 0; a < 4; ++a) lo4[a] = kInf, hi4[a] = -kInf;
    for (std::uint32_t i = begin; i < end; ++i)
      for (int a = 0; a < 4; ++a) {
        lo4[a] = std::min(lo4[a], items_[order_[i]].key[a]);
        hi4[a] = std::max(hi4[a], items_[order_[i]].key[a]);
      }
    int axis = 0;
    for (int a = 1; a < 4; ++a)
      if (hi4[a] - lo4[a] > hi4[axis] - lo4[axis]) axis = a;
    const double middle = 0.5 * (lo4[axis] + hi4[axis]);
    std::uint32_t mid = static_cast<std::uint32_t>(
        std::stable_partition(order_.begin() + begin, order_.begin() + end,
                              [&](Index p) { return items_[p].key[axis] < middle; }) -
        order_.begin());
    if (mid == begin || mid == end) {
      mid = begin + (end - begin) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](Index p, Index q) {
        const double mp = items_[p].key[axis], mq = items_[q].key[axis];
        return mp < mq || (mp == mq && p < q);
      });
    }
    return mid;
  }

  /// max over the vertex balls below of r − g·c.
  double max_offset(const Vec3& g, std::uint32_t begin, std::uint32_t end) const {
    double offset = -kInf;
    for (std::uint32_t i = begin; i < end; ++i) {
      const BuildItem& item = items_[order_[i]];
      for (int k = 0; k < item.count; ++k) offset = std::max(offset, item.balls[k][3] - g.dot(item.balls[k].head<3>()));
    }
    return offset;
  }

  std::vector<BvhNode>& nodes_;
  std::vector<Index>& order_;
  const std::vector<BuildItem>& items_;
};

}  // namespace

void EnvelopeBvh::pair_children(const std::vector<BvhNode>& nodes) {
  root_ = nodes[0];
  // Inner nodes keep their order (the root first); each gets the index of its pair.
  std::vector<std::uint32_t> pair_of(nodes.size(), 0);
  std::uint32_t inner = 0;
  for (std::size_t id = 0; id < nodes.size(); ++id)
    if (nodes[id].count == 0) pair_of[id] = inner++;
  pairs_.assign(inner, ChildPair{});
  for (std::size_t id = 0; id < nodes.size(); ++id) {
    if (nodes[id].count > 0) continue;
    ChildPair& pair = pairs_[pair_of[id]];
    const std::uint32_t left = static_cast<std::uint32_t>(id + 1), right = nodes[id].first;
    pair.set(0, nodes[left], pair_of[left]);
    pair.set(1, nodes[right], pair_of[right]);
  }
}

EnvelopeBvh::EnvelopeBvh(std::vector<PrimGeom> primitives) {
  const std::size_t np = primitives.size();
  std::vector<BuildItem> items(np);
  tbb::parallel_for(std::size_t{0}, np, [&](std::size_t i) { items[i] = build_item(primitives[i]); });
  for (const BuildItem& item : items) {
    bounds_.add(Vec3(item.box.lo.array() - item.rmax));
    bounds_.add(Vec3(item.box.hi.array() + item.rmax));
  }
  std::vector<Index> order(np);
  std::iota(order.begin(), order.end(), Index{0});
  if (np > 0) {
    std::vector<BvhNode> nodes(2 * np - 1);
    Builder(nodes, order, items).build(0, 0, static_cast<std::uint32_t>(np));
    pair_children(nodes);
  }
  bvh_index_.resize(np);
  for (std::size_t i = 0; i < np; ++i) bvh_index_[order[i]] = static_cast<Index>(i);
  geometry_.resize(np);
  tbb::parallel_for(std::size_t{0}, np, [&](std::size_t i) { geometry_[i] = primitives[order[i]]; });
  public_index_ = std::move(order);
}

}  // namespace medax::services::envelope_detail
