#pragma once
// Internal: a count with its noun, for the mesh checks' and repairs' messages.
#include <fmt/format.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace medax::services::detail {

/// "1 hole", "3 holes".
inline std::string plural(std::size_t n, std::string_view one, std::string_view many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

}  // namespace medax::services::detail
