#pragma once
// Running the built `medax` binary from a test, capturing its output and exit code.
#include "kernel_test_support.hpp"

#include <command_output.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

namespace medax::test {

/// The good test package's folder, for MEDAX_PLUGIN_PATH.
inline const std::string& good_plugins() {
  static const std::string path = plugin_dir("good").string();
  return path;
}

/// A pipeline on the cube with seed 3 and the given `stages:` lines.
inline std::string cube_pipeline(const std::string& stages) {
  return "input: " + data_file("cube.off") + "\nseed: 3\nstages:\n" + stages;
}

using Output = CommandOutput;

/// Runs `medax ARGS` with MEDAX_PLUGIN_PATH set to `plugin_path`, capturing stdout and stderr.
inline Output run_medax(const std::string& args, const std::string& plugin_path, const std::filesystem::path& dir) {
  const std::string binary = (std::filesystem::path(MEDAX_BINARY_DIR) / "bin" / "medax").string();
  return run_command("MEDAX_PLUGIN_PATH='" + plugin_path + "' '" + binary + "' " + args, dir / "stderr.txt");
}

/// Starts `medax ARGS...` in the background with MEDAX_PLUGIN_PATH set to `plugin_path`, stdout
/// and stderr into `dir`; returns its pid (the caller waits for it).
inline pid_t spawn_medax(const std::vector<std::string>& args, const std::string& plugin_path, const std::filesystem::path& dir) {
  const std::string binary = (std::filesystem::path(MEDAX_BINARY_DIR) / "bin" / "medax").string();
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::setenv("MEDAX_PLUGIN_PATH", plugin_path.c_str(), 1);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0) ::_exit(127);
    std::vector<char*> argv{const_cast<char*>(binary.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

}  // namespace medax::test
