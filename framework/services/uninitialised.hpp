#pragma once
// Arrays left uninitialised on allocation (internal to the geometry services): for large buffers
// that a parallel loop fills anyway, where zeroing them first (as std::vector does) would take one
// thread through every page.
#include <cstddef>
#include <memory>
#include <type_traits>

namespace medax::services {

/// An array of n T whose elements are not initialised (T must not need it).
template <typename T>
std::unique_ptr<T[]> uninitialised_array(std::size_t n) {
  static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
  return std::unique_ptr<T[]>(new T[n]);
}

}  // namespace medax::services
