#pragma once
// Text helpers shared by the mesh readers (io_mesh.cpp) and the point-set readers (io_points.cpp):
// whitespace tokens per line with line numbers, checked numbers, and errors that name the file.
// Internal to the kernel library.
#include <medax/io.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace medax::detail {

namespace fs = std::filesystem;

inline std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

[[noreturn]] inline void fail(const fs::path& path, const std::string& what) {
  throw IoError(fmt::format("{}: {}", path.string(), what));
}

inline std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file (check its permissions)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Lines of a text split into whitespace-separated tokens, '#' comments removed, with line numbers.
class Lines {
 public:
  /// `hash_comments`: '#' starts a comment (OFF, OBJ); PLY has none, and CGAL reads a '#' as text.
  explicit Lines(std::string_view text, bool hash_comments = true) : text_(text), hash_comments_(hash_comments) {}
  /// Next line with at least one token; false at the end of the text.
  bool next(std::vector<std::string_view>& tokens) {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      if (hash_comments_) line = line.substr(0, line.find('#'));
      tokens.clear();
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        const std::size_t b = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i > b) tokens.push_back(line.substr(b, i - b));
      }
      if (!tokens.empty()) return true;
    }
    return false;
  }
  std::size_t line() const { return line_; }
  std::size_t offset() const { return std::min(pos_, text_.size()); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  bool hash_comments_;
};

inline bool parse_integer(std::string_view token, long long& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

/// Parses a coordinate; the error names the element and the line.
inline double coordinate(const fs::path& path, std::string_view token, std::size_t line, std::size_t vertex) {
  const std::string s(token);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size())
    fail(path, fmt::format("line {}: vertex {}: '{}' is not a number", line, vertex, s));
  if (!std::isfinite(v))
    fail(path, fmt::format("line {}: vertex {} has the non-finite coordinate '{}' (fix or remove the vertex)",
                           line, vertex, s));
  return v;
}

/// What a PLY file holds, once its header and body passed the checks of the mesh reader.
struct PlyContents {
  long long vertices = 0;
  long long faces = 0;    ///< elements named 'face' (or 'tristrips')
  bool normals = false;   ///< the vertex element has nx, ny and nz
  /// Why CGAL's point reader cannot take the vertex element (x, y, z, nx, ny, nz must be float or
  /// double scalars, x, y, z once each); empty when it can.
  std::string point_problem;
};
/// Checks a PLY file as read_mesh does (header, counts against the size, body) and says what it
/// holds. Throws IoError naming the file and the line. Defined in io_mesh.cpp.
PlyContents check_ply_contents(const fs::path& path, const std::string& text);

/// Whether a file with a mesh extension (.off, .obj, .ply) holds vertices and no faces, judged
/// from its header or its lines; false when it cannot tell (read_mesh then reports the problem).
bool holds_points_only(const fs::path& path);

}  // namespace medax::detail
