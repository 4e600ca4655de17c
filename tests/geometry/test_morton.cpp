// Morton codes and the radix sort by code, against std::sort.
#include <medax/services/morton.hpp>

#include <catch2/catch.hpp>
#include <tbb/task_arena.h>

#include <algorithm>
#include <random>

using namespace medax;
using services::stable_sort_by_code;

namespace {

/// n (code, index) pairs in index order, codes below 2^bits, about one in four repeated.
std::vector<std::pair<std::uint64_t, Index>> random_items(std::size_t n, int bits, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::uint64_t mask = bits == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
  std::vector<std::pair<std::uint64_t, Index>> items(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool repeat = i > 0 && rng() % 4 == 0;
    items[i] = {repeat ? items[rng() % i].first : rng() & mask, static_cast<Index>(i)};
  }
  return items;
}

}  // namespace

TEST_CASE("Morton codes interleave the axes' bits, x lowest", "[morton]") {
  CHECK(services::morton_code(1, 0, 0) == 1);
  CHECK(services::morton_code(0, 1, 0) == 2);
  CHECK(services::morton_code(0, 0, 1) == 4);
  CHECK(services::morton_code(2, 0, 0) == 8);
  CHECK(services::morton_code(0x1fffff, 0x1fffff, 0x1fffff) == (std::uint64_t{1} << 63) - 1);
}

TEST_CASE("stable_sort_by_code orders by (code, index) as a comparison sort does", "[morton]") {
  for (const int bits : {1, 8, 11, 12, 27, 63, 64}) {
    for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{100000}}) {
      INFO(bits << " bits, " << n << " items");
      auto items = random_items(n, bits, 17 + bits);
      auto expected = items;
      std::sort(expected.begin(), expected.end());
      stable_sort_by_code(items);
      CHECK(items == expected);
    }
  }
}

TEST_CASE("stable_sort_by_code gives the same order on any number of threads", "[morton]") {
  const auto items = random_items(200000, 30, 5);
  std::vector<std::vector<std::pair<std::uint64_t, Index>>> sorted;
  for (const int threads : {1, 2, 3}) {
    auto copy = items;
    tbb::task_arena(threads).execute([&] { stable_sort_by_code(copy); });
    sorted.push_back(std::move(copy));
  }
  CHECK(sorted[0] == sorted[1]);
  CHECK(sorted[0] == sorted[2]);
}
