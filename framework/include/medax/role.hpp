#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace medax {

/// The six stage roles of a pipeline.
enum class Role { Conditioning, Extraction, Significance, Simplification, Connectivity, Evaluation };

std::string_view to_string(Role role);
std::optional<Role> role_from_string(std::string_view name);

}  // namespace medax
