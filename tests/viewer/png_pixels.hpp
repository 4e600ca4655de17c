#pragma once
// A PNG's pixels as RGB bytes (libpng), for checking what the browser drew.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace medax::test {

struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 bytes per pixel, rows top to bottom

  const std::uint8_t* at(int x, int y) const { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
};

/// Throws std::runtime_error when `file` is not a readable PNG.
Picture read_png(const std::filesystem::path& file);

/// Pixels that differ from `background` (r, g, b) by more than `tolerance` in some channel.
std::size_t count_not(const Picture& picture, const std::uint8_t background[3], int tolerance = 8);

/// Pixels where `a` and `b` (of the same size) differ by more than `tolerance` in some channel.
std::size_t count_different(const Picture& a, const Picture& b, int tolerance = 8);

}  // namespace medax::test
