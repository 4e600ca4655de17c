#pragma once
// Deterministic block-parallel loops: work split into fixed blocks, so per-block results
// gathered in block order do not depend on the thread count or schedule.
#include <cstddef>
#include <functional>

namespace medax::services {

/// Calls body(block, begin, end) for each block [b·size, min(n, (b+1)·size)) of 0..n: in
/// parallel (TBB) when `parallel`, otherwise in order.
void for_blocks(std::size_t n, std::size_t block_size, bool parallel,
                const std::function<void(std::size_t block, std::size_t begin, std::size_t end)>& body);

/// How many blocks for_blocks makes.
inline std::size_t block_count(std::size_t n, std::size_t block_size) { return (n + block_size - 1) / block_size; }

}  // namespace medax::services
