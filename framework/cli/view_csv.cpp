#include "view_csv.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace medax::cli {

namespace fs = std::filesystem;

bool is_experiment_folder(const fs::path& dir) {
  return fs::is_regular_file(dir / "results.csv") && fs::is_directory(dir / "jobs");
}

std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", file.string()));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    std::string& cell = rows.back().back();
    if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"')
      cell += text[++i];
    else if (c == '"')
      quoted = !quoted;
    else if (!quoted && c == ',')
      rows.back().emplace_back();
    else if (!quoted && c == '\n')
      rows.emplace_back(1);
    else if (c != '\r' || quoted)
      cell += c;
  }
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();  // after the last line's newline
  return rows;
}

}  // namespace medax::cli
