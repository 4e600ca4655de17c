#include <medax/kernel/param_table.hpp>

#include <fmt/format.h>

namespace medax {

namespace {
/// A table cell: pipes escaped, so a doc string cannot break the row.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::string code(const std::string& text) { return text.empty() ? std::string() : "`" + text + "`"; }
}  // namespace

std::string param_table_markdown(const StageInfo& info) {
  if (info.params.empty()) return "This stage has no parameters.\n";
  std::string out = "| parameter | type | default | range | unit | meaning |\n|---|---|---|---|---|---|\n";
  for (const ParamSpec& p : info.params)
    out += fmt::format("| {} | {} | {} | {} | {} | {} |\n", code(p.name), to_string(p.type), code(p.default_text()),
                       cell(p.range_text()), cell(p.unit), cell(p.doc));
  return out;
}

std::string param_block_markdown(const StageInfo& info) {
  return fmt::format("<!-- params: {} -->\n{}<!-- /params -->\n", info.name, param_table_markdown(info));
}

}  // namespace medax
