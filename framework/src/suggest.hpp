#pragma once
// "Did you mean ...?" for names typed by users.
#include <string>
#include <string_view>
#include <vector>

namespace medax::detail {

std::size_t edit_distance(std::string_view a, std::string_view b);
/// Up to `count` candidates within a plausible edit distance of `name`, closest first.
std::vector<std::string> closest_names(std::string_view name,
                                       const std::vector<std::string>& candidates,
                                       std::size_t count = 3);
/// " (did you mean 'a' or 'b'?)" or "".
std::string did_you_mean(const std::vector<std::string>& names);

}  // namespace medax::detail
