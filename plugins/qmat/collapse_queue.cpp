#include "collapse_queue.hpp"

#include <algorithm>

namespace medax::qmat {

namespace {
constexpr std::size_t kArity = 4;  // four 24-byte children: two cache lines
}

std::uint32_t CollapseQueue::store(const Vec4& sphere) {
  if (free_slots_.empty()) {
    spheres_.push_back(sphere);
    return static_cast<std::uint32_t>(spheres_.size() - 1);
  }
  const std::uint32_t slot = free_slots_.back();
  free_slots_.pop_back();
  spheres_[slot] = sphere;
  return slot;
}

void CollapseQueue::push_unordered(const QueuedCollapse& c) {
  heap_.push_back({c.cost, c.lo, c.hi, c.seq, store(c.sphere)});
}

void CollapseQueue::push(const QueuedCollapse& c) {
  if (size() >= sweep_above_) sweep_stale();
  push_unordered(c);
  sift_up(heap_.size() - 1);
}

QueuedCollapse CollapseQueue::pop() {
  const Key top = heap_[kRoot];
  heap_[kRoot] = heap_.back();
  heap_.pop_back();
  if (!empty()) sift_down(kRoot);
  free_slots_.push_back(top.slot);
  return {top.cost, top.lo, top.hi, top.seq, spheres_[top.slot]};
}

void CollapseQueue::sift_up(std::size_t at) {
  const Key moving = heap_[at];
  while (at > kRoot) {
    const std::size_t parent = at / kArity + 2;
    if (!after(heap_[parent], moving)) break;
    heap_[at] = heap_[parent];
    at = parent;
  }
  heap_[at] = moving;
}

/// (The grandchildren are requested while the children are compared: the next level's cache
/// misses then overlap this level's.)
void CollapseQueue::sift_down(std::size_t at) {
  const Key moving = heap_[at];
  const std::size_t n = heap_.size();
  for (;;) {
    const std::size_t first = kArity * at - 8;
    if (first >= n) break;
    const std::size_t last = std::min(first + kArity, n);
    for (std::size_t c = first; c < last && kArity * c - 8 < n; ++c) {
      __builtin_prefetch(&heap_[kArity * c - 8]);
      __builtin_prefetch(&heap_[kArity * c - 5]);  // the group's last key: its second line
    }
    std::size_t least = first;
    for (std::size_t c = first + 1; c < last; ++c)
      if (after(heap_[least], heap_[c])) least = c;
    if (!after(moving, heap_[least])) break;
    heap_[at] = heap_[least];
    at = least;
  }
  heap_[at] = moving;
}

void CollapseQueue::heapify() {
  for (std::size_t at = heap_.size() / kArity + 3; at-- > kRoot;)
    if (at < heap_.size()) sift_down(at);
  sweep_above_ = std::max<std::size_t>(size() + size() / 4, sweep_above_);
}

void CollapseQueue::sweep_stale() {
  auto live_end = std::partition(heap_.begin() + kRoot, heap_.end(), [&](const Key& k) { return !stale(k); });
  for (auto it = live_end; it != heap_.end(); ++it) free_slots_.push_back(it->slot);
  heap_.erase(live_end, heap_.end());
  heapify();
  sweep_above_ = std::max<std::size_t>(size() + size() / 4, 4096);
}

}  // namespace medax::qmat
