#include <medax/services/delaunay.hpp>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/parallel_for.h>

#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace medax::services {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<Index, K>;
using Cb = CGAL::Delaunay_triangulation_cell_base_3<K>;

template <typename Concurrency>
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb, Concurrency>;

template <typename Concurrency>
using Triangulation = CGAL::Delaunay_triangulation_3<K, Tds<Concurrency>>;

template <typename Dt>
DelaunayTetrahedralization extract(const Dt& dt, bool parallel) {
  if (dt.dimension() < 3)
    throw std::invalid_argument("the points are coplanar or collinear: a 3D Delaunay tetrahedralization needs "
                                "points spanning three dimensions");
  DelaunayTetrahedralization out;
  std::vector<typename Dt::Cell_handle> cells;
  cells.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) cells.push_back(c);
  // Deterministic cell order, whatever the insertion order or thread schedule: sort by corners.
  const auto key = [](typename Dt::Cell_handle c) {
    std::array<Index, 4> k{c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()};
    std::sort(k.begin(), k.end());
    return k;
  };
  std::vector<std::array<Index, 4>> keys(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) keys[i] = key(cells[i]);
  std::vector<std::size_t> order(cells.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  std::unordered_map<typename Dt::Cell_handle, std::int64_t, CGAL::Handle_hash_function> cell_index;
  cell_index.reserve(cells.size());
  for (std::size_t i = 0; i < order.size(); ++i) cell_index[cells[order[i]]] = static_cast<std::int64_t>(i);

  const std::size_t n = cells.size();
  out.cells.resize(n);
  out.neighbours.resize(n);
  out.circumcentres.resize(n);
  out.circumradii.resize(n);
  const auto fill = [&](std::size_t i) {
    const auto c = cells[order[i]];
    for (int k = 0; k < 4; ++k) {
      out.cells[i][k] = c->vertex(k)->info();
      const auto nb = c->neighbor(k);
      out.neighbours[i][k] = dt.is_infinite(nb) ? DelaunayTetrahedralization::kInfinite : cell_index.at(nb);
    }
    const K::Point_3 cc = CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
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
  // Merge exact duplicates first: each distinct position is represented by its smallest index.
  std::vector<Index> by_position(points.size());
  std::iota(by_position.begin(), by_position.end(), 0);
  const auto less = [&](Index a, Index b) {
    const Vec3 &p = points[a], &q = points[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
  };
  std::sort(by_position.begin(), by_position.end(), less);
  std::vector<Index> representative(points.size());
  for (std::size_t k = 0; k < by_position.size(); ++k) {
    const Index i = by_position[k];
    const bool duplicate = k > 0 && points[i] == points[by_position[k - 1]];
    representative[i] = duplicate ? representative[by_position[k - 1]] : i;
  }
  std::vector<std::pair<K::Point_3, Index>> input;
  std::vector<Index> vertex_point;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (representative[i] == i) {
      input.emplace_back(K::Point_3(points[i].x(), points[i].y(), points[i].z()), static_cast<Index>(i));
      vertex_point.push_back(static_cast<Index>(i));
    }
  std::vector<Index> point_vertex(points.size());
  for (std::size_t v = 0; v < vertex_point.size(); ++v) point_vertex[vertex_point[v]] = static_cast<Index>(v);
  for (std::size_t i = 0; i < points.size(); ++i) point_vertex[i] = point_vertex[representative[i]];

  DelaunayTetrahedralization out;
  if (options.parallel && points.size() > 10000) {
    CGAL::Bbox_3 box;
    for (const auto& [p, i] : input) box += p.bbox();
    typename Triangulation<CGAL::Parallel_tag>::Lock_data_structure locks(box, 50);
    Triangulation<CGAL::Parallel_tag> dt(input.begin(), input.end(), &locks);
    out = extract(dt, true);
  } else {
    Triangulation<CGAL::Sequential_tag> dt(input.begin(), input.end());
    out = extract(dt, options.parallel);
  }
  out.vertex_point = std::move(vertex_point);
  out.point_vertex = std::move(point_vertex);
  return out;
}

}  // namespace medax::services
