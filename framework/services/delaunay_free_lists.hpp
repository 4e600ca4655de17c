#pragma once
// The concurrent triangulation's vertex and cell infos, and its containers' per-thread free lists
// found through a native thread-local key (internal to services/delaunay.cpp).
//
// CGAL's Concurrent_compact_container keeps one free list per thread in a
// tbb::enumerable_thread_specific with TBB's default key (ets_no_key), whose local() hashes the
// thread id and probes a table: the container calls it for every cell it creates or erases, about
// a dozen times per inserted point, which cost 5-7 % of the concurrent insertion (perf, 1M koala
// samples). Specialized here for the triangulation's own vertex and cell types (marked by their
// info types, which serve nothing else), the free lists use ets_key_per_instance instead, whose
// local() is one pthread_getspecific. The containers' behaviour is otherwise the same.
#include <medax/geometry.hpp>

#include <CGAL/Concurrent_compact_container.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/enumerable_thread_specific.h>

#include <cstdint>

namespace medax::services::delaunay_detail {

/// A vertex's input point (its name in the output) and its rank (which orders the cells).
struct VertexInfo {
  Index point = 0;
  Index rank = 0;
};

/// A cell's number in the output (kInfinite for infinite cells), so that neighbours are read
/// directly instead of through a handle -> index map.
struct CellNumber {
  std::int64_t value = -1;
};

/// The free list type of a concurrent container of T, and the container's vertex and cell types.
template <typename T, typename Allocator>
using FreeList = CGAL::Free_list<T*, std::size_t, CGAL::Concurrent_compact_container<T, Allocator>>;
template <typename GT, typename Vb>
using Vertex = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, GT, Vb>;
template <typename GT, typename Cb>
using Cell = CGAL::Triangulation_cell_base_with_info_3<CellNumber, GT, Cb>;

/// The per-thread free lists of a concurrent container of T, keyed per instance.
template <typename T, typename Allocator>
using FreeListsPerInstance = tbb::enumerable_thread_specific<FreeList<T, Allocator>,
                                                             tbb::cache_aligned_allocator<FreeList<T, Allocator>>,
                                                             tbb::ets_key_per_instance>;

}  // namespace medax::services::delaunay_detail

namespace tbb::detail::d1 {

template <typename GT, typename Cb, typename Allocator>
class enumerable_thread_specific<
    medax::services::delaunay_detail::FreeList<medax::services::delaunay_detail::Cell<GT, Cb>, Allocator>,
    cache_aligned_allocator<
        medax::services::delaunay_detail::FreeList<medax::services::delaunay_detail::Cell<GT, Cb>, Allocator>>,
    ets_no_key>
    : public medax::services::delaunay_detail::FreeListsPerInstance<medax::services::delaunay_detail::Cell<GT, Cb>,
                                                                     Allocator> {};

template <typename GT, typename Vb, typename Allocator>
class enumerable_thread_specific<
    medax::services::delaunay_detail::FreeList<medax::services::delaunay_detail::Vertex<GT, Vb>, Allocator>,
    cache_aligned_allocator<
        medax::services::delaunay_detail::FreeList<medax::services::delaunay_detail::Vertex<GT, Vb>, Allocator>>,
    ets_no_key>
    : public medax::services::delaunay_detail::FreeListsPerInstance<medax::services::delaunay_detail::Vertex<GT, Vb>,
                                                                     Allocator> {};

}  // namespace tbb::detail::d1
