#pragma once
// The `medax` sub-commands. Each returns the process exit code:
// 0 success, 1 a stage failed, 2 bad usage or an invalid pipeline.
#include <filesystem>
#include <string>
#include <vector>

namespace medax::cli {

struct RunArgs {
  std::filesystem::path pipeline;
  std::filesystem::path input;
  std::filesystem::path out;
  std::vector<std::string> settings;
  bool quiet = false;
};

int list_plugins();
int describe(const std::string& name);
int validate(const RunArgs& args);
int run(const RunArgs& args);

}  // namespace medax::cli
