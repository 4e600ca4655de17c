#include "diagnostics.hpp"

#include "suggest.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

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

void Diagnostics::duplicate_keys(const YAML::Node& root) {
  // An alias shares its anchor's node, so each collection is walked once (known by its position
  // in the file): a document of nested aliases cannot make the walk exponential.
  std::set<std::size_t> walked;
  std::vector<YAML::Node> pending{root};
  std::vector<std::pair<YAML::Node, std::string>> found;
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (!node.IsMap() && !node.IsSequence()) continue;
    if (!node.Mark().is_null() && !walked.insert(static_cast<std::size_t>(node.Mark().pos)).second) continue;
    if (node.IsSequence()) {
      for (const YAML::Node& item : node) pending.push_back(item);
      continue;
    }
    std::map<std::string, YAML::Mark> first;  // scalar key -> where it first appears
    for (const auto& kv : node) {
      pending.push_back(kv.first);
      pending.push_back(kv.second);
      if (!kv.first.IsScalar()) continue;
      const auto [it, fresh] = first.emplace(kv.first.Scalar(), kv.first.Mark());
      if (fresh) continue;
      const std::string earlier =
          it->second.is_null() ? std::string("earlier") : fmt::format("first at line {}", it->second.line + 1);
      found.emplace_back(kv.first, fmt::format("duplicate key '{}' ({}); remove one (YAML keeps only the first)",
                                               kv.first.Scalar(), earlier));
    }
  }
  // Reported in file order. Sorted by index: assigning a YAML::Node rewrites the document.
  std::vector<std::size_t> order(found.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return found[a].first.Mark().pos < found[b].first.Mark().pos;
  });
  for (std::size_t i : order) error(found[i].first, std::move(found[i].second));
}

void Diagnostics::throw_if_any() {
  if (!diagnostics_.empty()) throw PipelineError(take());
}

}  // namespace medax::detail
