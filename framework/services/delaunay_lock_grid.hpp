#pragma once
// The grid of locks of the concurrent Delaunay insertion (internal to services/delaunay.cpp):
// CGAL's Spatial_lock_grid_3<Tag_non_blocking> (a thread that finds a grid cell locked by
// another gives up at once; its caller releases everything and retries the point), with the
// list of the cells each thread holds behind a native thread-local key (ets_key_per_instance)
// instead of TBB's lookup by a hash of the thread id, which CGAL's grid does at every lock taken
// and every release. Only the calls of CGAL's concurrent triangulation are redefined; the grid,
// the per-thread copies of it and their meaning are CGAL's.
#include <CGAL/Spatial_lock_grid_3.h>
#include <tbb/cache_aligned_allocator.h>
#include <tbb/enumerable_thread_specific.h>

#include <stdexcept>
#include <vector>

namespace medax::services::delaunay_detail {

class LockGrid : public CGAL::Spatial_lock_grid_3<CGAL::Tag_non_blocking> {
  using Base = CGAL::Spatial_lock_grid_3<CGAL::Tag_non_blocking>;

 public:
  using Base::Base;

  /// Locks the grid cell of p for this thread (true), or finds it locked by another (false).
  /// Only lock_radius 0 (the cell itself): the Delaunay insertion asks for no more.
  template <typename P3>
  bool try_lock(const P3& p, int lock_radius = 0) {
    if (lock_radius != 0) throw std::logic_error("delaunay LockGrid: only lock radius 0 is supported");
    const int cell = get_grid_index(p);
    bool* mine = get_thread_local_grid();
    if (mine[cell]) return true;
    bool expected = false;
    if (!m_grid[cell].compare_exchange_strong(expected, true)) return false;
    mine[cell] = true;
    held_.local().push_back(cell);
    return true;
  }
  void unlock_all_points_locked_by_this_thread() { unlock_all_but(-1); }
  template <typename P3>
  void unlock_all_tls_locked_locations_but_one_point(const P3& p) {
    unlock_all_but(get_grid_index(p));
  }

 private:
  /// Releases the cells this thread holds, but `keep` (-1: none).
  void unlock_all_but(int keep) {
    std::vector<int>& held = held_.local();
    bool* mine = get_thread_local_grid();
    bool kept = false;
    for (const int cell : held) {
      if (cell == keep) {
        kept = true;
        continue;
      }
      m_grid[cell] = false;
      mine[cell] = false;
    }
    held.clear();
    if (kept) held.push_back(keep);
  }

  tbb::enumerable_thread_specific<std::vector<int>, tbb::cache_aligned_allocator<std::vector<int>>,
                                  tbb::ets_key_per_instance>
      held_;
};

}  // namespace medax::services::delaunay_detail
