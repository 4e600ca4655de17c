#include <medax/services/delaunay.hpp>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace medax::services {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<Index, K>;
// Each cell stores its index in the output (-1 for infinite cells), so neighbours are read
// directly instead of through a handle -> index map.
using Cb = CGAL::Triangulation_cell_base_with_info_3<std::int64_t, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb, CGAL::Sequential_tag>;
using Triangulation = CGAL::Delaunay_triangulation_3<K, Tds>;

using ExactKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;

/// Circumcentre of (a, b, c, d), equidistant from the four corners up to the final rounding.
/// The double construction is exact enough for well-shaped cells; for nearly flat ones (e.g.
/// four nearly cocircular points, common on meshes with rings of vertices) its error can reach
/// the size of the cell, so those are recomputed with exact rationals.
K::Point_3 robust_circumcenter(const K::Point_3& a, const K::Point_3& b, const K::Point_3& c, const K::Point_3& d) {
  const K::Point_3 cc = CGAL::circumcenter(a, b, c, d);
  const double ra = std::sqrt(CGAL::squared_distance(cc, a));
  const double tolerance = 1e-12 * (ra + std::abs(a.x()) + std::abs(a.y()) + std::abs(a.z()));
  bool accurate = std::isfinite(ra);
  for (const K::Point_3* p : {&b, &c, &d})
    accurate = accurate && std::abs(std::sqrt(CGAL::squared_distance(cc, *p)) - ra) <= tolerance;
  if (accurate) return cc;
  const auto exact = [](const K::Point_3& p) { return ExactKernel::Point_3(p.x(), p.y(), p.z()); };
  const ExactKernel::Point_3 e = CGAL::circumcenter(exact(a), exact(b), exact(c), exact(d));
  return K::Point_3(CGAL::to_double(e.x()), CGAL::to_double(e.y()), CGAL::to_double(e.z()));
}

/// A cell's corners sorted, packed into one 128-bit key for a fast deterministic sort.
struct CellKey {
  std::uint64_t hi, lo;
  std::uint32_t cell;  // position in the CGAL iteration order
  bool operator<(const CellKey& o) const { return hi != o.hi ? hi < o.hi : lo < o.lo; }
};

DelaunayTetrahedralization extract(Triangulation& dt, bool parallel) {
  if (dt.dimension() < 3)
    throw std::invalid_argument("the points are coplanar or collinear: a 3D Delaunay tetrahedralization needs "
                                "points spanning three dimensions");
  const std::size_t n = dt.number_of_finite_cells();
  std::vector<Triangulation::Cell_handle> cells;
  cells.reserve(n);
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) cells.push_back(c);
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) c->info() = DelaunayTetrahedralization::kInfinite;

  // Deterministic cell order, whatever the insertion history: sort by sorted corners.
  std::vector<CellKey> keys(n);
  const auto make_key = [&](std::size_t i) {
    const auto c = cells[i];
    std::array<Index, 4> k{c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()};
    std::sort(k.begin(), k.end());
    keys[i] = {(std::uint64_t{k[0]} << 32) | k[1], (std::uint64_t{k[2]} << 32) | k[3], static_cast<std::uint32_t>(i)};
  };
  if (parallel) {
    tbb::parallel_for(std::size_t{0}, n, make_key);
    tbb::parallel_sort(keys.begin(), keys.end());
  } else {
    for (std::size_t i = 0; i < n; ++i) make_key(i);
    std::sort(keys.begin(), keys.end());
  }
  for (std::size_t i = 0; i < n; ++i) cells[keys[i].cell]->info() = static_cast<std::int64_t>(i);

  DelaunayTetrahedralization out;
  out.cells.resize(n);
  out.neighbours.resize(n);
  out.circumcentres.resize(n);
  out.circumradii.resize(n);
  const auto fill = [&](std::size_t i) {
    const auto c = cells[keys[i].cell];
    for (int k = 0; k < 4; ++k) {
      out.cells[i][k] = c->vertex(k)->info();
      out.neighbours[i][k] = c->neighbor(k)->info();  // kInfinite for infinite cells
    }
    const K::Point_3 cc = robust_circumcenter(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                                              c->vertex(3)->point());
    out.circumcentres[i] = Vec3(cc.x(), cc.y(), cc.z());
    out.circumradii[i] = std::sqrt(CGAL::squared_distance(cc, c->vertex(0)->point()));
  };
  if (parallel) tbb::parallel_for(std::size_t{0}, n, fill);
  else for (std::size_t i = 0; i < n; ++i) fill(i);
  return out;
}

}  // namespace

DelaunayTetrahedralization delaunay_tetrahedralize(const std::vector<Vec3>& points, const DelaunayOptions& options) {
  if (points.size() >= (std::size_t{1} << 32) - 1)
    throw std::invalid_argument("delaunay_tetrahedralize: too many points for 32-bit indices");
  // Merge exact duplicates first: each distinct position is represented by its smallest index.
  std::vector<Index> by_position(points.size());
  std::iota(by_position.begin(), by_position.end(), 0);
  const auto less = [&](Index a, Index b) {
    const Vec3 &p = points[a], &q = points[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
  };
  if (options.parallel) tbb::parallel_sort(by_position.begin(), by_position.end(), less);
  else std::sort(by_position.begin(), by_position.end(), less);
  std::vector<Index> representative(points.size());
  for (std::size_t k = 0; k < by_position.size(); ++k) {
    const Index i = by_position[k];
    const bool duplicate = k > 0 && points[i] == points[by_position[k - 1]];
    representative[i] = duplicate ? representative[by_position[k - 1]] : i;
  }
  std::vector<std::pair<K::Point_3, Index>> input;
  input.reserve(points.size());
  std::vector<Index> vertex_point;
  vertex_point.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (representative[i] == i) {
      input.emplace_back(K::Point_3(points[i].x(), points[i].y(), points[i].z()), static_cast<Index>(i));
      vertex_point.push_back(static_cast<Index>(i));
    }
  std::vector<Index> point_vertex(points.size());
  for (std::size_t v = 0; v < vertex_point.size(); ++v) point_vertex[vertex_point[v]] = static_cast<Index>(v);
  for (std::size_t i = 0; i < points.size(); ++i) point_vertex[i] = point_vertex[representative[i]];

  // Sequential insertion (CGAL sorts the range along a Hilbert curve first). CGAL's parallel
  // insertion was measured 5-8x slower than this on 2 shared cores (lock contention), from 26k
  // to 1M points, so it is not used; the per-cell work below is parallel.
  Triangulation dt(input.begin(), input.end());
  DelaunayTetrahedralization out = extract(dt, options.parallel);
  out.vertex_point = std::move(vertex_point);
  out.point_vertex = std::move(point_vertex);
  return out;
}

DelaunayTetrahedralization delaunay_tetrahedralize_alongside(const std::vector<Vec3>& points,
                                                             const DelaunayOptions& options,
                                                             const std::function<void()>& alongside) {
  if (!options.parallel) {
    alongside();
    return delaunay_tetrahedralize(points, options);
  }
  tbb::task_group group;
  group.run(alongside);
  DelaunayTetrahedralization dt;
  try {
    dt = delaunay_tetrahedralize(points, options);
  } catch (...) {
    group.wait();
    throw;
  }
  group.wait();  // rethrows a failure of `alongside`
  return dt;
}

}  // namespace medax::services
