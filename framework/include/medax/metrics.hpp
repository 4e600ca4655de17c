#pragma once
#include <map>
#include <string>

namespace medax {

/// Named scalar results of an evaluation stage, ordered by name (deterministic output).
using Metrics = std::map<std::string, double>;

}  // namespace medax
