#include "diagnostics.hpp"

#include "suggest.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace medax::detail {

void Diagnostics::error(const YAML::Node& at, std::string message) {
  Diagnostic d{file_, 0, 0, std::move(message)};
  for (const auto& [node, where] : overridden_)
    if (node.is(at)) {
      d.file = where;  // a value given with --set has no position in the file
      diagnostics_.push_back(std::move(d));
      return;
    }
  if (at.IsDefined() && !at.Mark().is_null()) {
    d.line = at.Mark().line + 1;
    d.column = at.Mark().column + 1;
  }
  diagnostics_.push_back(std::move(d));
}

void Diagnostics::error_at(const std::string& where, std::string message) {
  diagnostics_.push_back(Diagnostic{where, 0, 0, std::move(message)});
}

void Diagnostics::unknown_keys(const YAML::Node& map, const std::vector<std::string>& known, const char* what) {
  for (const auto& kv : map) {
    const std::string key = kv.first.Scalar();  // empty for a non-scalar key: reported below
    if (std::find(known.begin(), known.end(), key) == known.end())
      error(kv.first, fmt::format("unknown {} key '{}'{}; known keys: {}", what, key,
                                  did_you_mean(closest_names(key, known)), fmt::join(known, ", ")));
  }
}

void Diagnostics::throw_if_any() {
  if (!diagnostics_.empty()) throw PipelineError(take());
}

}  // namespace medax::detail
