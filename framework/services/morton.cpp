#include <medax/services/morton.hpp>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>

namespace medax::services {

namespace {

constexpr int kDigitBits = 11;
constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;

using Item = std::pair<std::uint64_t, Index>;

/// The stable scatter of `from` into `to` by the digit at `shift`: each slice counts its digits,
/// then writes its items from where the slices before it (and the smaller digits) end.
void scatter_by_digit(const std::vector<Item>& from, std::vector<Item>& to, int shift, std::size_t slices) {
  const std::size_t n = from.size();
  const auto slice_begin = [&](std::size_t s) { return n * s / slices; };
  const auto digit = [shift](const Item& item) { return (item.first >> shift) & (kBuckets - 1); };
  std::vector<std::array<std::size_t, kBuckets>> next(slices);
  tbb::parallel_for(std::size_t{0}, slices, [&](std::size_t s) {
    next[s].fill(0);
    for (std::size_t i = slice_begin(s); i < slice_begin(s + 1); ++i) ++next[s][digit(from[i])];
  });
  for (std::size_t d = 0, at = 0; d < kBuckets; ++d)
    for (auto& slice : next) at += std::exchange(slice[d], at);
  tbb::parallel_for(std::size_t{0}, slices, [&](std::size_t s) {
    for (std::size_t i = slice_begin(s); i < slice_begin(s + 1); ++i) to[next[s][digit(from[i])]++] = from[i];
  });
}

}  // namespace

void stable_sort_by_code(std::vector<Item>& items) {
  std::uint64_t used = 0;  // the bits set in any code: only those digits need a pass
  for (const Item& item : items) used |= item.first;
  const std::size_t slices = std::clamp<std::size_t>(tbb::this_task_arena::max_concurrency(), 1, 8);
  std::vector<Item> buffer(items.size());
  for (int shift = 0; shift < 64 && (used >> shift) != 0; shift += kDigitBits) {
    scatter_by_digit(items, buffer, shift, slices);
    items.swap(buffer);
  }
}

}  // namespace medax::services
