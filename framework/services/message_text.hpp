#pragma once
// Internal: building the mesh checks' and repairs' messages without fmt (not linked here).
#include <sstream>
#include <string>

namespace medax::services::detail {

/// Concatenates its arguments with operator<<, numbers with 6 significant digits.
template <typename... Args>
std::string cat(const Args&... args) {
  std::ostringstream s;
  s.precision(6);
  (s << ... << args);
  return s.str();
}

/// "1 hole", "3 holes".
inline std::string plural(std::size_t n, const char* one, const char* many) { return cat(n, ' ', n == 1 ? one : many); }

}  // namespace medax::services::detail
