#pragma once
// Reading and writing the run folder's JSON files (metrics, timings, status).
#include <nlohmann/json.hpp>

#include <filesystem>

namespace medax::detail {

/// The parsed file, or null when it is missing or not valid JSON.
nlohmann::json read_json_file(const std::filesystem::path& path);
/// Writes `value` indented, atomically.
void write_json_file(const std::filesystem::path& path, const nlohmann::json& value);

}  // namespace medax::detail
