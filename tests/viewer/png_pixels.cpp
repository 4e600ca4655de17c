#include "png_pixels.hpp"

#include <png.h>

#include <cstdlib>
#include <stdexcept>

namespace medax::test {

Picture read_png(const std::filesystem::path& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, file.c_str()))
    throw std::runtime_error(file.string() + ": not a readable PNG: " + image.message);
  image.format = PNG_FORMAT_RGB;
  Picture picture;
  picture.width = static_cast<int>(image.width);
  picture.height = static_cast<int>(image.height);
  picture.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, picture.rgb.data(), 0, nullptr))
    throw std::runtime_error(file.string() + ": cannot decode the PNG: " + image.message);
  return picture;
}

namespace {
bool differs(const std::uint8_t* a, const std::uint8_t* b, int tolerance) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(a[c]) - int(b[c])) > tolerance) return true;
  return false;
}
}  // namespace

std::size_t count_not(const Picture& picture, const std::uint8_t background[3], int tolerance) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < picture.rgb.size(); i += 3) n += differs(&picture.rgb[i], background, tolerance);
  return n;
}

std::size_t count_different(const Picture& a, const Picture& b, int tolerance) {
  if (a.rgb.size() != b.rgb.size()) throw std::runtime_error("the pictures differ in size");
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < a.rgb.size(); i += 3) n += differs(&a.rgb[i], &b.rgb[i], tolerance);
  return n;
}

}  // namespace medax::test
