#include <medax/services/blocks.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>

namespace medax::services {

void for_blocks(std::size_t n, std::size_t block_size, bool parallel,
                const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
  const std::size_t blocks = block_count(n, block_size);
  const auto run = [&](std::size_t b) { body(b, b * block_size, std::min(n, (b + 1) * block_size)); };
  if (parallel) tbb::parallel_for(std::size_t{0}, blocks, run);
  else for (std::size_t b = 0; b < blocks; ++b) run(b);
}

}  // namespace medax::services
