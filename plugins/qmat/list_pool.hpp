#pragma once
// Lists of indices, one per vertex, kept in one array instead of one heap block each: the
// collapse mesh's adjacency and face lists. A list grows in place while it has room, and moves
// to the end of the array with twice the room when it has none (its old place is left unused).
// Growing a list can move the array: views taken before are then invalid, so loops that grow
// lists read the list they walk by position.
#include <medax/geometry.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace medax::qmat {

class ListPool {
 public:
  /// A read-only view of one list.
  struct View {
    const Index* first;
    const Index* last;
    const Index* begin() const { return first; }
    const Index* end() const { return last; }
    std::size_t size() const { return static_cast<std::size_t>(last - first); }
    Index operator[](std::size_t k) const { return first[k]; }
  };

  ListPool() = default;
  /// Empty lists with room[v] entries for list v, laid out one after the other.
  explicit ListPool(const std::vector<std::size_t>& room);

  View operator[](std::size_t v) const {
    const Index* first = items_.data() + spans_[v].first;
    return {first, first + spans_[v].size};
  }
  void push_back(std::size_t v, Index x);
  /// Inserts x into the sorted list v unless it is there.
  void insert_sorted(std::size_t v, Index x);
  /// Removes x from the sorted list v if it is there.
  void erase_sorted(std::size_t v, Index x);
  template <typename Pred>
  void erase_if(std::size_t v, Pred&& pred) {
    Index* first = data(v);
    spans_[v].size = static_cast<std::uint32_t>(std::remove_if(first, first + spans_[v].size, pred) - first);
  }
  /// Sorts list v and drops repeats (in place: lists are independent, so in parallel too).
  void sort_unique(std::size_t v);
  void clear(std::size_t v) { spans_[v].size = 0; }

 private:
  struct Span {
    std::size_t first = 0;
    std::uint32_t size = 0, room = 0;
  };
  Index* data(std::size_t v) { return items_.data() + spans_[v].first; }
  void grow(std::size_t v);

  std::vector<Span> spans_;
  std::vector<Index> items_;
};

}  // namespace medax::qmat
