#pragma once
// The lazy priority queue of Q-MAT's collapse loop. An entry is the collapse of edge (lo, hi)
// costed after change number `seq` of the mesh; the owner numbers its changes 1, 2, … and stamps
// a vertex with the number of the change that last moved or killed it, so an entry is stale (and
// skipped by the caller) once an endpoint's stamp is above its seq. For speed (popping stale
// entries was a tenth of the work), the heap is 4-ary over 24-byte keys whose sibling groups
// lie in two cache lines (the storage is 128-byte aligned, the root three keys in), the
// optimal spheres live in a slot store beside
// it, the first entries are heapified at once, and stale entries are swept out whenever the heap
// has grown by a quarter since the last sweep (most entries go stale before they reach the top).
// The order is the total order (cost, lo, hi), so the pops of live entries depend on none of it.
#include "slab_quadric.hpp"

#include <medax/geometry.hpp>

#include <cstdint>
#include <new>
#include <vector>

namespace medax::qmat {

struct QueuedCollapse {
  double cost = 0;
  Index lo = 0, hi = 0;
  std::uint32_t seq = 0;  ///< the number of the mesh's last change when it was costed
  Vec4 sphere = Vec4::Zero();
};

class CollapseQueue {
 public:
  /// `stamps` (one per vertex, owned by the caller) tells stale entries apart in the sweeps.
  explicit CollapseQueue(const std::vector<std::uint32_t>& stamps) : stamps_(stamps) {}

  void push(const QueuedCollapse& c);
  /// Room for `n` entries (the first ones, pushed unordered, without moving them as they come).
  void reserve(std::size_t n) {
    heap_.reserve(kRoot + n);
    spheres_.reserve(n);
  }
  /// Adds an entry without ordering the heap; call heapify() before the next pop or push.
  void push_unordered(const QueuedCollapse& c);
  void heapify();
  bool empty() const { return size() == 0; }
  std::size_t size() const { return heap_.size() - kRoot; }
  /// Removes and returns the least entry by (cost, lo, hi).
  QueuedCollapse pop();

 private:
  struct Key {
    double cost;
    Index lo, hi;
    std::uint32_t seq;
    std::uint32_t slot;  ///< index of the sphere in spheres_
  };
  static_assert(sizeof(Key) == 24, "a sibling group of four keys must lie in two cache lines");
  /// Heap order: true when a comes after b (a min-heap on cost, ties by the edge's indices).
  static bool after(const Key& a, const Key& b) {
    if (a.cost != b.cost) return a.cost > b.cost;
    if (a.lo != b.lo) return a.lo > b.lo;
    return a.hi > b.hi;
  }
  bool stale(const Key& k) const { return stamps_[k.lo] > k.seq || stamps_[k.hi] > k.seq; }
  /// Storage aligned to 128 bytes: with the root three keys in, every sibling group (96 bytes,
  /// starting at a multiple of 96) lies in two cache lines.
  template <typename T>
  struct GroupAligned {
    using value_type = T;
    GroupAligned() = default;
    template <typename U>
    GroupAligned(const GroupAligned<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(128))); }
    void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(128)); }
    friend bool operator==(const GroupAligned&, const GroupAligned&) { return true; }
  };
  /// The root's position in heap_: the children of position p are then 4p − 8 … 4p − 5, one
  /// group.
  static constexpr std::size_t kRoot = 3;
  std::uint32_t store(const Vec4& sphere);
  void sift_up(std::size_t at);
  void sift_down(std::size_t at);
  void sweep_stale();

  const std::vector<std::uint32_t>& stamps_;
  std::vector<Key, GroupAligned<Key>> heap_ = std::vector<Key, GroupAligned<Key>>(kRoot);
  std::vector<Vec4> spheres_;
  std::vector<std::uint32_t> free_slots_;
  std::size_t sweep_above_ = 4096;
};

}  // namespace medax::qmat
