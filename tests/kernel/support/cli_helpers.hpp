#pragma once
// Running the built `medax` binary from a test, capturing its output and exit code.
#include "kernel_test_support.hpp"

#include <cstdio>
#include <sys/wait.h>

namespace medax::test {

struct Output {
  int code = -1;
  std::string out, err;
};

/// Runs `medax ARGS` with MEDAX_PLUGIN_PATH set to `plugin_path`, capturing stdout and stderr.
inline Output run_medax(const std::string& args, const std::string& plugin_path, const std::filesystem::path& dir) {
  const std::filesystem::path err_file = dir / "stderr.txt";
  const std::string command = "MEDAX_PLUGIN_PATH='" + plugin_path + "' '" +
                              (std::filesystem::path(MEDAX_BINARY_DIR) / "bin" / "medax").string() + "' " + args + " 2>'" +
                              err_file.string() + "'";
  Output result;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.out.append(buffer, n);
  const int status = ::pclose(pipe);
  result.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = read_text(err_file);
  return result;
}

}  // namespace medax::test
