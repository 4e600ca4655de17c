#include "view_ply.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace medax::cli {

namespace fs = std::filesystem;

const PlyProperty* PlyTable::find(const std::string& property) const {
  for (const PlyProperty& p : properties)
    if (p.name == property) return &p;
  return nullptr;
}

namespace {

bool is_integer_type(const std::string& type) {
  return type != "float" && type != "double" && type != "float32" && type != "float64";
}

/// The element layout of the header: per element, its columns (a list column has name "").
struct Layout {
  PlyTable table;
  std::vector<int> columns;  ///< per column: index in table.properties, or -1 for the list
};

class PlyText {
 public:
  explicit PlyText(const fs::path& path) : path_(path), in_(path) {
    if (!in_) throw std::runtime_error(fmt::format("{}: cannot open the file", path.string()));
  }
  bool line(std::istringstream& words) {
    std::string text;
    if (!std::getline(in_, text)) return false;
    ++line_;
    words.clear();
    words.str(text);
    return true;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", path_.string(), line_, what));
  }

 private:
  fs::path path_;
  std::ifstream in_;
  std::size_t line_ = 0;
};

std::vector<Layout> read_header(PlyText& text) {
  std::vector<Layout> layouts;
  std::istringstream words;
  std::string keyword;
  if (!text.line(words) || !(words >> keyword) || keyword != "ply") text.fail("not a PLY file (no 'ply' line)");
  while (text.line(words)) {
    if (!(words >> keyword) || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") return layouts;
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format != "ascii") text.fail(fmt::format("{} PLY is not read by the viewer; medax writes ASCII", format));
    } else if (keyword == "element") {
      Layout layout;
      if (!(words >> layout.table.name >> layout.table.rows)) text.fail("an element line is 'element NAME COUNT'");
      layouts.push_back(std::move(layout));
    } else if (keyword == "property") {
      if (layouts.empty()) text.fail("a property before any element");
      std::string type, name;
      words >> type;
      if (type == "list") {
        layouts.back().columns.push_back(-1);
        continue;
      }
      if (!(words >> name)) text.fail("a property line is 'property TYPE NAME'");
      PlyTable& table = layouts.back().table;
      layouts.back().columns.push_back(static_cast<int>(table.properties.size()));
      table.properties.push_back({name, is_integer_type(type), {}});
      table.properties.back().values.reserve(table.rows);
    }
  }
  text.fail("the header has no end_header line");
}

/// The next number of a row. medax writes an undefined field value as `nan` (ET's et_c where no
/// medial curve passes), which `>>` does not read; strtod does.
bool next_number(std::istringstream& words, double& value) {
  std::string word;
  if (!(words >> word)) return false;
  char* end = nullptr;
  value = std::strtod(word.c_str(), &end);
  return end == word.c_str() + word.size();
}

void read_row(PlyText& text, std::istringstream& words, Layout& layout, std::size_t row) {
  PlyTable& table = layout.table;
  for (int column : layout.columns) {
    double value = 0;
    if (!next_number(words, value)) text.fail(fmt::format("element '{}' row {}: a value is missing or not a number", table.name, row));
    if (column >= 0) {
      table.properties[column].values.push_back(value);
      continue;
    }
    if (!(value >= 0 && value <= 1000) || value != static_cast<int>(value))
      text.fail(fmt::format("element '{}' row {}: a list count of {} (0 to 1000 expected)", table.name, row, value));
    std::vector<std::uint32_t> corners(static_cast<std::size_t>(value));
    for (std::uint32_t& c : corners)
      if (!(words >> c))
        text.fail(fmt::format("element '{}' row {}: the list is shorter than its count", table.name, row));
    for (std::size_t k = 2; k < corners.size(); ++k) {
      table.triangles.insert(table.triangles.end(), {corners[0], corners[k - 1], corners[k]});
      table.triangle_row.push_back(row);
    }
  }
}

}  // namespace

std::map<std::string, PlyTable> read_ply_tables(const fs::path& path) {
  PlyText text(path);
  std::vector<Layout> layouts = read_header(text);
  std::map<std::string, PlyTable> tables;
  std::istringstream words;
  for (Layout& layout : layouts) {
    for (std::size_t row = 0; row < layout.table.rows; ++row) {
      if (!text.line(words))
        text.fail(
            fmt::format("the file ends inside element '{}' (row {} of {})", layout.table.name, row, layout.table.rows));
      read_row(text, words, layout, row);
    }
    tables[layout.table.name] = std::move(layout.table);
  }
  return tables;
}

}  // namespace medax::cli
