#pragma once
// Running a shell command line from a test: its stdout, its stderr (through a file) and its exit code.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace medax::test {

struct CommandOutput {
  int code = -1;
  std::string out, err;
};

/// Runs `command` with its stderr into `err_file`, capturing stdout.
inline CommandOutput run_command(const std::string& command, const std::filesystem::path& err_file) {
  CommandOutput result;
  FILE* pipe = ::popen((command + " 2>'" + err_file.string() + "'").c_str(), "r");
  REQUIRE(pipe);
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.out.append(buffer, n);
  const int status = ::pclose(pipe);
  result.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_file);
  std::ostringstream text;
  text << err.rdbuf();
  result.err = text.str();
  return result;
}

}  // namespace medax::test
