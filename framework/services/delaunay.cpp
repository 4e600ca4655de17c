#include <medax/services/delaunay.hpp>

#include "delaunay_free_lists.hpp"
#include "delaunay_lock_grid.hpp"
#include "uninitialised.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <iterator>
#include <memory>
#include <type_traits>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace medax::services {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using delaunay_detail::CellNumber;
using delaunay_detail::VertexInfo;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, K>;
using Cb = CGAL::Triangulation_cell_base_with_info_3<CellNumber, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
// Small inputs: CGAL's sequential range insertion, as medax always did (the exact results the
// plugins' tests were written against).
using SequentialTriangulation =
    CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb, CGAL::Sequential_tag>>;
// Large inputs: a concurrent data structure, where threads insert points at once, each locking
// the cells of its conflict zone through a grid of locks over the bounding box. A thread that
// meets a lock held by another releases its own and retries the point (non-blocking): on surface
// samples, whose big interior cells make threads meet often, this spends about 15% less CPU
// than CGAL's default priority locks, where the thread of higher priority spins until the
// other lets go (and, on a loaded machine, the other may be preempted meanwhile). The grid is
// CGAL's non-blocking one with a cheaper per-thread list of held locks (delaunay_lock_grid.hpp).
using delaunay_detail::LockGrid;
using Triangulation = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb, CGAL::Parallel_tag>,
                                                     CGAL::Default, LockGrid>;

using ExactKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;

/// From this many points on, the concurrent triangulation; below, the sequential one (faster
/// there, and its corner order is the one the plugins' small test cases were written against).
constexpr std::size_t kConcurrentFrom = 50000;
/// Rounds smaller than this are inserted by one thread: locking costs more than it gains there.
constexpr std::size_t kParallelRound = 20000;
/// Cells per axis of the lock grid (CGAL's Mesh_3 default).
constexpr int kLockGridCells = 50;

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

/// Canonical corner order of a positively oriented cell: corner positions sorted by point index,
/// with the last two swapped when that sort is an odd permutation (the orientation stays positive).
/// The concurrent build leaves corners rotated by its history; this order does not depend on it.
/// (The sequential build's history is fixed, so its order is kept as it is.)
std::array<int, 4> canonical_corners(const std::array<Index, 4>& v, bool canonical) {
  if (!canonical) return {0, 1, 2, 3};
  std::array<int, 4> order{0, 1, 2, 3};
  int swaps = 0;
  for (int i = 1; i < 4; ++i)  // insertion sort, counting transpositions
    for (int j = i; j > 0 && v[order[j]] < v[order[j - 1]]; --j, ++swaps) std::swap(order[j], order[j - 1]);
  if (swaps % 2) std::swap(order[2], order[3]);
  return order;
}

/// Runs f(i) for i in [0, n), in parallel or not.
template <typename F>
void for_each_index(std::size_t n, bool parallel, const F& f) {
  if (parallel) tbb::parallel_for(std::size_t{0}, n, f);
  else for (std::size_t i = 0; i < n; ++i) f(i);
}

/// Threads that can run here: the arena's, capped by any tbb::global_control in force.
int usable_threads() {
  const std::size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return static_cast<int>(std::min<std::size_t>(tbb::this_task_arena::max_concurrency(), allowed));
}

/// Runs f(begin, end) on chunks covering [0, n), in parallel or not: loops that look ahead
/// within their chunk.
template <typename F>
void for_each_chunk(std::size_t n, bool parallel, const F& f) {
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
  else f(std::size_t{0}, n);
}

/// Asks the cache for `x` ahead of its use: the per-cell loops below jump through the
/// triangulation's memory, and would otherwise wait on a cache miss at nearly every cell.
template <typename T>
void prefetch(const T& x, bool for_writing = false) {
  if (for_writing) __builtin_prefetch(static_cast<const void*>(&x), 1);
  else __builtin_prefetch(static_cast<const void*>(&x));
}

/// How far ahead (in cells) the loops fetch a cell, and its corners and neighbours.
constexpr std::size_t kFetchCellAhead = 16;
constexpr std::size_t kFetchAroundAhead = 8;

/// A cell and the key that orders it (trivially constructible: arrays of them are not zeroed).
template <typename Cell>
struct KeyedCell {
  std::array<Index, 4> key;
  Cell* cell;
};

/// The cell type of a cell handle.
template <typename CellHandle>
using CellOf = std::remove_reference_t<decltype(*std::declval<CellHandle>())>;

/// Each cell with its corners' ranks sorted ascending (its key), in the container's order.
template <typename CellHandle>
std::unique_ptr<KeyedCell<CellOf<CellHandle>>[]> keyed_cells(const std::vector<CellHandle>& cells, bool parallel) {
  auto keyed = uninitialised_array<KeyedCell<CellOf<CellHandle>>>(cells.size());
  for_each_chunk(cells.size(), parallel, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kFetchAroundAhead < end)
        for (int k = 0; k < 4; ++k) prefetch(cells[i + kFetchAroundAhead]->vertex(k)->info());
      const auto& c = cells[i];
      auto& key = keyed[i].key;
      key = {c->vertex(0)->info().rank, c->vertex(1)->info().rank, c->vertex(2)->info().rank,
             c->vertex(3)->info().rank};
      std::sort(key.begin(), key.end());
      keyed[i].cell = &*c;
    }
  });
  return keyed;
}

/// The cells in a deterministic order, whatever the insertion history: by their corners' ranks
/// (all below `ranks`), each cell's ranks sorted ascending and compared lexicographically. A
/// counting sort on the smallest rank, then a sort of each (small) bucket on the other three:
/// no comparison sort of all cells. The counting sort runs on a few slices of the cells at once;
/// keys are distinct (a cell is its four corners), so the order does not depend on the slices.
template <typename CellHandle>
std::vector<CellOf<CellHandle>*> cells_in_canonical_order(const std::vector<CellHandle>& cells, std::size_t ranks,
                                                          bool parallel) {
  using Keyed = KeyedCell<CellOf<CellHandle>>;
  const std::unique_ptr<Keyed[]> keyed = keyed_cells(cells, parallel);
  const std::size_t n = cells.size();
  const std::size_t slices = parallel ? std::clamp<std::size_t>(usable_threads(), 1, 8) : 1;
  const auto slice_begin = [&](std::size_t s) { return n * s / slices; };
  // next[s][r]: the count of slice s's cells in bucket r, then where the next of them goes.
  std::vector<std::vector<std::uint32_t>> next(slices);
  for_each_index(slices, parallel, [&](std::size_t s) {
    next[s].assign(ranks, 0);
    for (std::size_t i = slice_begin(s); i < slice_begin(s + 1); ++i) ++next[s][keyed[i].key[0]];
  });
  std::vector<std::size_t> start(ranks + 1, 0);
  for (std::size_t r = 0, at = 0; r < ranks; ++r) {
    start[r] = at;
    for (auto& slice : next) at += std::exchange(slice[r], static_cast<std::uint32_t>(at));
    start[r + 1] = at;
  }
  const std::unique_ptr<Keyed[]> sorted = uninitialised_array<Keyed>(n);
  for_each_index(slices, parallel, [&](std::size_t s) {
    for (std::size_t i = slice_begin(s); i < slice_begin(s + 1); ++i) sorted[next[s][keyed[i].key[0]]++] = keyed[i];
  });
  const auto by_key = [](const Keyed& a, const Keyed& b) { return a.key < b.key; };
  for_each_index(ranks, parallel, [&](std::size_t r) {
    if (start[r + 1] - start[r] > 1) std::sort(&sorted[start[r]], &sorted[start[r + 1]], by_key);
  });
  std::vector<CellOf<CellHandle>*> order(n);
  for_each_index(n, parallel, [&](std::size_t i) { order[i] = sorted[i].cell; });
  return order;
}

/// Output arrays for n cells, allocated (and zeroed) side by side.
DelaunayTetrahedralization allocate_cells(std::size_t n, bool parallel) {
  DelaunayTetrahedralization out;
  const auto cells = [&] { out.cells.resize(n); };
  const auto neighbours = [&] { out.neighbours.resize(n); };
  const auto centres = [&] {
    out.circumcentres.resize(n);
    out.circumradii.resize(n);
  };
  if (parallel) {
    tbb::parallel_invoke(cells, neighbours, centres);
  } else {
    cells();
    neighbours();
    centres();
  }
  return out;
}

/// Writes cell i of the output from its triangulation cell c (numbered already, as are its
/// neighbours).
template <typename CellHandle>
void write_cell(DelaunayTetrahedralization& out, std::size_t i, const CellHandle& c, bool canonical) {
  const std::array<Index, 4> v{c->vertex(0)->info().point, c->vertex(1)->info().point, c->vertex(2)->info().point,
                               c->vertex(3)->info().point};
  const std::array<int, 4> corner = canonical_corners(v, canonical);
  for (int k = 0; k < 4; ++k) {
    out.cells[i][k] = v[corner[k]];
    out.neighbours[i][k] = c->neighbor(corner[k])->info().value;  // kInfinite for infinite cells
  }
  const auto& p0 = c->vertex(corner[0])->point();
  const K::Point_3 cc = robust_circumcenter(p0, c->vertex(corner[1])->point(), c->vertex(corner[2])->point(),
                                            c->vertex(corner[3])->point());
  out.circumcentres[i] = Vec3(cc.x(), cc.y(), cc.z());
  out.circumradii[i] = std::sqrt(CGAL::squared_distance(cc, p0));
}

/// The finite cells, in the container's order.
template <typename Triangulation>
std::vector<typename Triangulation::Cell_handle> finite_cells(const Triangulation& dt) {
  std::vector<typename Triangulation::Cell_handle> cells;
  cells.reserve(dt.number_of_cells());  // finite and infinite: O(1), where counting the finite walks them
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) cells.push_back(c);
  return cells;
}

template <typename Triangulation>
DelaunayTetrahedralization extract(Triangulation& dt, std::size_t ranks, bool parallel, bool canonical) {
  if (dt.dimension() < 3)
    throw std::invalid_argument("the points are coplanar or collinear: a 3D Delaunay tetrahedralization needs "
                                "points spanning three dimensions");
  // Only the infinite cells keep kInfinite: the finite ones are numbered below.
  std::vector<typename Triangulation::Cell_handle> infinite;
  dt.incident_cells(dt.infinite_vertex(), std::back_inserter(infinite));
  for (const auto& c : infinite) c->info().value = DelaunayTetrahedralization::kInfinite;
  const auto ordered = cells_in_canonical_order(finite_cells(dt), ranks, parallel);
  const std::size_t n = ordered.size();
  for_each_chunk(n, parallel, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kFetchCellAhead < end) prefetch(ordered[i + kFetchCellAhead]->info(), true);
      ordered[i]->info().value = static_cast<std::int64_t>(i);
    }
  });

  DelaunayTetrahedralization out = allocate_cells(n, parallel);
  for_each_chunk(n, parallel, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kFetchCellAhead < end) {
        prefetch(*ordered[i + kFetchCellAhead]);
        prefetch(ordered[i + kFetchCellAhead]->info());
      }
      if (i + kFetchAroundAhead < end)
        for (int k = 0; k < 4; ++k) {
          prefetch(ordered[i + kFetchAroundAhead]->neighbor(k)->info());
          prefetch(*ordered[i + kFetchAroundAhead]->vertex(k));
        }
      write_cell(out, i, ordered[i], canonical);
    }
  });
  return out;
}

/// Each point's representative: exact duplicates merge into the one with the smallest index.
/// Sorts (x, y, z, index) records, so that the sort compares without jumping to the points.
std::vector<Index> merge_duplicates(const std::vector<Vec3>& points, bool parallel) {
  using Record = std::tuple<double, double, double, Index>;
  std::vector<Record> by_position(points.size());
  for_each_index(points.size(), parallel, [&](std::size_t i) {
    by_position[i] = {points[i].x(), points[i].y(), points[i].z(), static_cast<Index>(i)};
  });
  if (parallel) tbb::parallel_sort(by_position.begin(), by_position.end());
  else std::sort(by_position.begin(), by_position.end());
  std::vector<Index> representative(points.size());
  Index first = 0;  // the smallest index at the current position
  for (std::size_t k = 0; k < by_position.size(); ++k) {
    const auto& [x, y, z, i] = by_position[k];
    const bool duplicate = k > 0 && x == std::get<0>(by_position[k - 1]) && y == std::get<1>(by_position[k - 1]) &&
                           z == std::get<2>(by_position[k - 1]);
    if (!duplicate) first = i;
    representative[i] = first;
  }
  return representative;
}

/// Insertion order: a biased randomized insertion order (Amenta, Choi & Rote 2003), as CGAL's
/// spatial_sort makes: a fixed-seed shuffle cut into rounds, each 8 times the one before, each
/// sorted along a Hilbert curve. Returns the order and where each round begins (and the end).
std::pair<std::vector<std::size_t>, std::vector<std::size_t>> brio_order(const std::vector<K::Point_3>& points,
                                                                         bool parallel) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937_64 rng(0x5eed);
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng() % i]);
  std::vector<std::size_t> bounds{order.size()};
  while (bounds.back() > 1000) bounds.push_back(bounds.back() / 8);
  bounds.push_back(0);
  std::reverse(bounds.begin(), bounds.end());
  // The sort moves (point, index) pairs, so that its comparisons read the points in place (the
  // same comparisons and moves as sorting indices, so the same order).
  using Located = std::pair<K::Point_3, std::size_t>;
  std::vector<Located> located(order.size());
  for_each_index(order.size(), parallel, [&](std::size_t k) { located[k] = {points[order[k]], order[k]}; });
  using Traits = CGAL::Spatial_sort_traits_adapter_3<K, CGAL::First_of_pair_property_map<Located>>;
  const Traits traits;
  for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
    if (parallel)
      CGAL::hilbert_sort<CGAL::Parallel_tag>(located.begin() + bounds[r], located.begin() + bounds[r + 1], traits);
    else
      CGAL::hilbert_sort(located.begin() + bounds[r], located.begin() + bounds[r + 1], traits);
  }
  for_each_index(order.size(), parallel, [&](std::size_t k) { order[k] = located[k].second; });
  return {std::move(order), std::move(bounds)};
}

/// The info of the i-th point of the insertion order. Its rank is that position reversed, so that
/// nearly every cell is ranked by a corner of the last round, which is sorted along a Hilbert
/// curve: cells numbered along it are close in memory, for the extraction and for every method
/// that walks them.
VertexInfo info_at(const std::vector<Index>& infos, const std::vector<std::size_t>& order, std::size_t i) {
  return {infos[order[i]], static_cast<Index>(order.size() - 1 - i)};
}

/// Inserts points[order[begin..end)] with several threads, each holding the locks of its
/// conflict zone and retrying a point when another thread holds one of them (as CGAL's own
/// parallel range insertion, which inserts its whole order at once where we go round by round).
void insert_concurrently(Triangulation& dt, const std::vector<K::Point_3>& points, const std::vector<Index>& infos,
                         const std::vector<std::size_t>& order, std::size_t begin, std::size_t end,
                         Triangulation::Vertex_handle hint) {
  tbb::enumerable_thread_specific<Triangulation::Vertex_handle> hints(hint);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end), [&](const tbb::blocked_range<std::size_t>& range) {
    Triangulation::Vertex_handle& local = hints.local();
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const K::Point_3& p = points[order[i]];
      for (bool done = false; !done;) {
        if (dt.try_lock_vertex(local) && dt.try_lock_point(p)) {
          bool locked = false;
          const Triangulation::Vertex_handle v = dt.insert(p, local, &locked);
          dt.unlock_all_elements();
          if (locked) {
            v->info() = info_at(infos, order, i);
            local = v;
            done = true;
          }
        } else {
          dt.unlock_all_elements();
        }
      }
    }
  });
}

/// The Delaunay triangulation of the points, vertex infos set. Small rounds of the insertion
/// order go in sequentially, large ones concurrently once the triangulation is 3D; the
/// triangulation is the same either way (CGAL breaks cospherical ties by a symbolic
/// perturbation, which does not depend on the insertion order).
void triangulate(Triangulation& dt, const std::vector<K::Point_3>& points, const std::vector<Index>& infos,
                 bool parallel) {
  const auto [order, bounds] = brio_order(points, parallel);
  // On one thread, locking only costs (about 15%): insert everything sequentially.
  parallel = parallel && usable_threads() > 1;
  Triangulation::Vertex_handle hint;
  for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
    const std::size_t begin = bounds[r], end = bounds[r + 1];
    if (parallel && end - begin >= kParallelRound && dt.dimension() == 3) {
      insert_concurrently(dt, points, infos, order, begin, end, hint);
      continue;
    }
    for (std::size_t i = begin; i < end; ++i) {
      hint = dt.insert(points[order[i]], hint);
      hint->info() = info_at(infos, order, i);
    }
  }
}

CGAL::Bbox_3 bounding_box(const std::vector<K::Point_3>& points) {
  CGAL::Bbox_3 box;
  for (const K::Point_3& p : points) box += p.bbox();
  return box;
}

DelaunayTetrahedralization tetrahedralize(const std::vector<Vec3>& points, const DelaunayOptions& options) {
  if (points.size() >= (std::size_t{1} << 32) - 1)
    throw std::invalid_argument("delaunay_tetrahedralize: too many points for 32-bit indices");
  const std::vector<Index> representative = merge_duplicates(points, options.parallel);
  std::vector<K::Point_3> input;
  input.reserve(points.size());
  std::vector<Index> vertex_point;
  vertex_point.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (representative[i] == i) {
      input.emplace_back(points[i].x(), points[i].y(), points[i].z());
      vertex_point.push_back(static_cast<Index>(i));
    }
  std::vector<Index> point_vertex(points.size());
  for (std::size_t v = 0; v < vertex_point.size(); ++v) point_vertex[vertex_point[v]] = static_cast<Index>(v);
  for (std::size_t i = 0; i < points.size(); ++i) point_vertex[i] = point_vertex[representative[i]];

  DelaunayTetrahedralization out;
  if (input.size() < kConcurrentFrom) {
    // Cells numbered by their corners' point indices.
    std::vector<std::pair<K::Point_3, VertexInfo>> with_info(input.size());
    for (std::size_t v = 0; v < input.size(); ++v) with_info[v] = {input[v], {vertex_point[v], vertex_point[v]}};
    SequentialTriangulation dt(with_info.begin(), with_info.end());  // sorted along a Hilbert curve first
    out = extract(dt, points.size(), options.parallel, false);
  } else {
    // The lock grid is only used when a round is inserted concurrently.
    LockGrid locks(bounding_box(input), kLockGridCells);
    Triangulation dt(K(), options.parallel ? &locks : nullptr);
    triangulate(dt, input, vertex_point, options.parallel);
    out = extract(dt, input.size(), options.parallel, true);
  }
  out.vertex_point = std::move(vertex_point);
  out.point_vertex = std::move(point_vertex);
  return out;
}

}  // namespace

DelaunayTetrahedralization delaunay_tetrahedralize(const std::vector<Vec3>& points, const DelaunayOptions& options) {
  if (options.max_threads <= 0) return tetrahedralize(points, options);
  tbb::task_arena arena(options.max_threads);
  return arena.execute([&] { return tetrahedralize(points, options); });
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
