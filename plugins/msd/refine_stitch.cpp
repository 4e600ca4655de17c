#include "refine_stitch.hpp"

#include <algorithm>
#include <limits>

namespace medax::msd::refine {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The two loops walked the same way round: the inner one from `start`, the outer one reversed
/// from the vertex nearest to inner[start] on ∂P^ρ0.
struct Walk {
  std::vector<Index> a, b;
};

Walk make_walk(const std::vector<Index>& inner, const std::vector<Index>& outer, std::size_t start,
               const std::vector<FramedPoint>& points) {
  Walk walk;
  const std::size_t n = inner.size(), m = outer.size();
  for (std::size_t i = 0; i < n; ++i) walk.a.push_back(inner[(start + i) % n]);
  const Vec3& from = points[walk.a[0]].projected;
  std::size_t nearest = 0;
  for (std::size_t j = 1; j < m; ++j)
    if ((points[outer[j]].projected - from).norm() < (points[outer[nearest]].projected - from).norm()) nearest = j;
  for (std::size_t k = 0; k < m; ++k) walk.b.push_back(outer[(nearest + m - k) % m]);
  return walk;
}

bool consistent(const std::vector<FramedPoint>& points, Index p, Index q, Index r) {
  return consistent_triangle(points[p], points[q], points[r]);
}

/// cost(i, k): the cheapest band from the start edge (a0, b0) to the edge (a_i, b_k); the step
/// into (i, k) adds triangle (a_i, a_{i−1}, b_k) (`from_a`) or (b_{k−1}, b_k, a_i).
std::optional<std::vector<Tri>> stitch_walk(const Walk& walk, const std::vector<FramedPoint>& points) {
  const std::size_t n = walk.a.size(), m = walk.b.size(), width = m + 1;
  const auto a = [&](std::size_t i) { return walk.a[i % n]; };
  const auto b = [&](std::size_t k) { return walk.b[k % m]; };
  std::vector<double> cost((n + 1) * width, kInfinity);
  std::vector<char> from_a((n + 1) * width, 0);
  cost[0] = 0;
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t k = 0; k <= m; ++k) {
      if (i == 0 && k == 0) continue;
      const double length = (points[a(i)].projected - points[b(k)].projected).norm();
      double best = kInfinity;
      if (i > 0 && cost[(i - 1) * width + k] < kInfinity && consistent(points, a(i), a(i - 1), b(k))) {
        best = cost[(i - 1) * width + k] + length;
        from_a[i * width + k] = 1;
      }
      if (k > 0 && cost[i * width + k - 1] + length < best && consistent(points, b(k - 1), b(k), a(i))) {
        best = cost[i * width + k - 1] + length;
        from_a[i * width + k] = 0;
      }
      cost[i * width + k] = best;
    }
  if (cost[n * width + m] == kInfinity) return std::nullopt;
  std::vector<Tri> band;
  for (std::size_t i = n, k = m; i > 0 || k > 0;) {
    if (from_a[i * width + k]) {
      band.push_back({a(i), a(i - 1), b(k)});
      --i;
    } else {
      band.push_back({b(k - 1), b(k), a(i)});
      --k;
    }
  }
  std::reverse(band.begin(), band.end());
  return band;
}

/// The ear (c[i−1], c[i], c[i+1]) of the polygon c can be cut.
bool is_ear(const std::vector<Index>& c, std::size_t i, const std::vector<FramedPoint>& points) {
  const std::size_t n = c.size();
  const Index p = c[(i + n - 1) % n], q = c[i], r = c[(i + 1) % n];
  if (!consistent(points, p, q, r)) return false;
  const Vec3 apex = (points[p].base + points[q].base + points[r].base) / 3;
  for (std::size_t k = 0; k < n; ++k) {
    const Index y = c[k];
    if (y != p && y != q && y != r &&
        in_cone(points[p].projected, points[q].projected, points[r].projected, apex, points[y].projected))
      return false;
  }
  return true;
}

}  // namespace

std::optional<std::vector<Tri>> cap_loop(const std::vector<Index>& loop, const std::vector<FramedPoint>& points) {
  // The cap lies on the right of the border: walk the loop backwards so it is on the left.
  std::vector<Index> c(loop.rbegin(), loop.rend());
  std::vector<Tri> cap;
  while (c.size() > 3) {
    std::size_t best = c.size();
    double shortest = kInfinity;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double length =
          (points[c[(i + c.size() - 1) % c.size()]].projected - points[c[(i + 1) % c.size()]].projected).norm();
      if (length < shortest && is_ear(c, i, points)) {
        shortest = length;
        best = i;
      }
    }
    if (best == c.size()) return std::nullopt;
    cap.push_back({c[(best + c.size() - 1) % c.size()], c[best], c[(best + 1) % c.size()]});
    c.erase(c.begin() + static_cast<std::ptrdiff_t>(best));
  }
  if (c.size() < 3 || !consistent(points, c[0], c[1], c[2])) return std::nullopt;
  cap.push_back({c[0], c[1], c[2]});
  return cap;
}

std::optional<std::vector<Tri>> stitch_band(const std::vector<Index>& inner, const std::vector<Index>& outer,
                                            const std::vector<FramedPoint>& points) {
  if (inner.size() < 3 || outer.size() < 3) return std::nullopt;
  // A few starting edges around the inner loop: the nearest pair can sit where no consistent
  // band passes (a concave corner of the patch).
  constexpr std::size_t kStarts = 4;
  for (std::size_t s = 0; s < kStarts; ++s)
    if (auto band = stitch_walk(make_walk(inner, outer, s * inner.size() / kStarts, points), points)) return band;
  return std::nullopt;
}

}  // namespace medax::msd::refine
