#pragma once
// The priority queue of weighted sample elimination (private to the Poisson-disk sampling).
#include <medax/geometry.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace medax::services::poisson_detail {

/// The candidates by current weight, largest first, ties to the larger candidate index
/// (`original`), so the order of the pops is fully determined. Weights only ever decrease, which
/// makes a lazy queue exact: the candidates are cut into blocks of kBlock consecutive ones (in the
/// graph's spatial numbering, so a removal's neighbours share few blocks), and a 4-ary max-heap
/// holds one entry per block, its heaviest candidate as of the block's last scan. A decrease or a
/// removal writes the current weight alone. An entry whose candidate still has the weight it was
/// keyed by is the block's true maximum (the others only lost weight since the scan); at the top,
/// such an entry is the global maximum, and any other top is rescanned and sifted down. The
/// pops therefore come in the order of an exact heap, from weights lowered by the same
/// subtractions in the same order, while a decrease touches nearby memory only.
class EliminationQueue {
 public:
  EliminationQueue(std::vector<double> weights, const std::vector<Index>& original)
      : current_(std::move(weights)), original_(original), queued_(current_.size()) {
    heap_.resize((current_.size() + kBlock - 1) / kBlock);
    for (std::size_t b = 0; b < heap_.size(); ++b) heap_[b] = heaviest_of(b);
    for (std::size_t i = heap_.size() / kArity + 1; i-- > 0;) sift_down(i);
  }
  /// The candidates not removed yet.
  std::size_t size() const { return queued_; }
  /// Removes and returns the candidate of largest current weight (the queue must not be empty).
  Index pop() {
    while (heap_.front().weight != current_[heap_.front().id]) refresh_top();
    const Index top = heap_.front().id;
    current_[top] = kRemoved;
    --queued_;
    refresh_top();
    return top;
  }
  /// The candidate the next pop returns unless its weight was lowered since it was keyed.
  Index likely_next() const { return heap_.front().id; }
  /// Lowers the weight of candidate i (a removed candidate stays removed).
  void decrease(Index i, double by) { current_[i] -= by; }
  /// Whether candidate i is still queued.
  bool contains(Index i) const { return current_[i] != kRemoved; }

 private:
  struct alignas(16) Entry {
    double weight;
    Index original, id;
    bool above(const Entry& o) const { return weight > o.weight || (weight == o.weight && original > o.original); }
  };
  static constexpr std::size_t kBlock = 32;
  static constexpr std::size_t kArity = 4;
  static constexpr double kRemoved = -std::numeric_limits<double>::infinity();

  /// The heaviest queued candidate of block b (weight kRemoved when none is left). The candidate
  /// indices are read for ties only.
  Entry heaviest_of(std::size_t b) const {
    const std::size_t first = b * kBlock, last = std::min(current_.size(), first + kBlock);
    std::size_t best = first;
    for (std::size_t i = first + 1; i < last; ++i)
      if (current_[i] > current_[best] || (current_[i] == current_[best] && original_[i] > original_[best])) best = i;
    return {current_[best], original_[best], static_cast<Index>(best)};
  }
  void refresh_top() {
    heap_.front() = heaviest_of(heap_.front().id / kBlock);
    sift_down(0);
  }
  void sift_down(std::size_t i) {
    const Entry item = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      const std::size_t first = kArity * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      for (std::size_t c = first + 1; c < std::min(first + kArity, n); ++c)
        if (heap_[c].above(heap_[best])) best = c;
      if (!heap_[best].above(item)) break;
      heap_[i] = heap_[best];
      i = best;
    }
    heap_[i] = item;
  }

  std::vector<double> current_;
  const std::vector<Index>& original_;
  std::size_t queued_;
  std::vector<Entry> heap_;
};

}  // namespace medax::services::poisson_detail
