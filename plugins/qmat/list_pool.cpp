#include "list_pool.hpp"

#include <algorithm>

namespace medax::qmat {

ListPool::ListPool(const std::vector<std::size_t>& room) : spans_(room.size()) {
  std::size_t total = 0;
  for (std::size_t v = 0; v < room.size(); ++v) {
    spans_[v].first = total;
    spans_[v].room = static_cast<std::uint32_t>(room[v]);
    total += room[v];
  }
  items_.reserve(2 * total);  // room for the lists that move as they grow, without copying all
  items_.resize(total);
}

void ListPool::grow(std::size_t v) {
  Span& s = spans_[v];
  const std::size_t first = items_.size();
  const std::uint32_t room = std::max<std::uint32_t>(2 * s.room, 4);
  items_.resize(first + room);
  std::copy_n(items_.data() + s.first, s.size, items_.data() + first);
  s.first = first;
  s.room = room;
}

void ListPool::push_back(std::size_t v, Index x) {
  if (spans_[v].size == spans_[v].room) grow(v);
  data(v)[spans_[v].size++] = x;
}

void ListPool::insert_sorted(std::size_t v, Index x) {
  Index* first = data(v);
  Index* last = first + spans_[v].size;
  Index* at = std::lower_bound(first, last, x);
  if (at != last && *at == x) return;
  const std::size_t k = static_cast<std::size_t>(at - first);
  if (spans_[v].size == spans_[v].room) grow(v);
  first = data(v);
  std::copy_backward(first + k, first + spans_[v].size, first + spans_[v].size + 1);
  first[k] = x;
  ++spans_[v].size;
}

void ListPool::erase_sorted(std::size_t v, Index x) {
  Index* first = data(v);
  Index* last = first + spans_[v].size;
  Index* at = std::lower_bound(first, last, x);
  if (at == last || *at != x) return;
  std::copy(at + 1, last, at);
  --spans_[v].size;
}

void ListPool::sort_unique(std::size_t v) {
  Index* first = data(v);
  Index* last = first + spans_[v].size;
  std::sort(first, last);
  spans_[v].size = static_cast<std::uint32_t>(std::unique(first, last) - first);
}

}  // namespace medax::qmat
