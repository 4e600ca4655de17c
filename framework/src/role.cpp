#include <medax/role.hpp>

#include <array>

namespace medax {

namespace {
constexpr std::array<std::pair<Role, std::string_view>, 6> kRoleNames{{
    {Role::Conditioning, "conditioning"},
    {Role::Extraction, "extraction"},
    {Role::Significance, "significance"},
    {Role::Simplification, "simplification"},
    {Role::Connectivity, "connectivity"},
    {Role::Evaluation, "evaluation"},
}};
}  // namespace

std::string_view to_string(Role role) {
  for (const auto& [r, name] : kRoleNames)
    if (r == role) return name;
  return "unknown";
}

std::optional<Role> role_from_string(std::string_view name) {
  for (const auto& [r, n] : kRoleNames)
    if (n == name) return r;
  return std::nullopt;
}

}  // namespace medax
