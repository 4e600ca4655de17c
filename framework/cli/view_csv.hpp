#pragma once
// An experiment's folder as `medax run` writes it (docs/experiments.md): results.csv and jobs/.
#include <filesystem>
#include <string>
#include <vector>

namespace medax::cli {

/// True when `dir` is an experiment's folder (results.csv and jobs/), not a run folder.
bool is_experiment_folder(const std::filesystem::path& dir);

/// The rows of a CSV file as `medax run` writes results.csv (RFC 4180 quoting: a quoted cell may
/// hold commas, doubled quotes and line breaks). Throws naming the file when it cannot be read.
std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& file);

}  // namespace medax::cli
