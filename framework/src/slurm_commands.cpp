// Calling the Slurm client commands and parsing their output.
#include "slurm_commands.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

namespace medax::slurm {

CommandResult run_command(const std::vector<std::string>& argv) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) return {127, "cannot create a pipe"};
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    return {127, "cannot start a process (fork failed)"};
  }
  if (pid == 0) {
    ::dup2(pipe_fds[1], STDOUT_FILENO);
    ::dup2(pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    const std::string why = fmt::format("cannot run {}: {}", argv[0], std::strerror(errno));
    (void)!::write(STDOUT_FILENO, why.data(), why.size());
    std::_Exit(127);
  }
  ::close(pipe_fds[1]);
  CommandResult result;
  char buffer[4096];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    result.output.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::vector<std::string> lines_of(const std::string& output) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

bool is_final_state(const std::string& state) {
  static const std::set<std::string> final_states{"COMPLETED", "FAILED",    "TIMEOUT",   "OUT_OF_MEMORY",
                                                  "NODE_FAIL", "CANCELLED", "PREEMPTED", "BOOT_FAIL",
                                                  "DEADLINE",  "REVOKED",   "SPECIAL_EXIT"};
  // sacct writes "CANCELLED by 0".
  return final_states.count(state.substr(0, state.find(' '))) > 0;
}

namespace {

/// "INDEX|STATE" lines (squeue -o '%K|%T') or "ID_INDEX|STATE" lines (sacct -P -o JobID,State).
std::map<std::size_t, std::string> parse_states(const std::string& text) {
  std::map<std::size_t, std::string> states;
  for (const std::string& line : lines_of(text)) {
    const auto bar = line.find('|');
    if (bar == std::string::npos) continue;
    std::string index = line.substr(0, bar);
    index = index.substr(index.find('_') == std::string::npos ? 0 : index.find('_') + 1);
    if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos) continue;  // "[3-9%2]" rows
    states[std::stoul(index)] = line.substr(bar + 1, line.find_last_not_of(' ') - bar);
  }
  return states;
}

}  // namespace

std::map<std::size_t, std::string> array_task_states(const std::string& array_id, std::size_t& active) {
  std::map<std::size_t, std::string> states =
      parse_states(run_command({"squeue", "-h", "-r", "-t", "all", "-j", array_id, "-o", "%K|%T"}).output);
  if (states.empty()) {
    const CommandResult sacct = run_command({"sacct", "-n", "-P", "-X", "-j", array_id, "-o", "JobID,State"});
    if (sacct.exit_code == 0) states = parse_states(sacct.output);
  }
  active = 0;
  for (const auto& [index, state] : states) active += is_final_state(state) ? 0 : 1;
  return states;
}

std::optional<double> duration_seconds(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789:-") != std::string::npos) return std::nullopt;
  double days = 0;
  std::string rest = text;
  const bool has_days = rest.find('-') != std::string::npos;  // DAYS-HOURS[:MINUTES[:SECONDS]]
  if (const auto dash = rest.find('-'); has_days) {
    if (dash == 0 || rest.find('-', dash + 1) != std::string::npos) return std::nullopt;
    days = std::stod(rest.substr(0, dash));
    rest = rest.substr(dash + 1);
  }
  std::vector<double> parts;
  std::istringstream in(rest);
  for (std::string part; std::getline(in, part, ':');) {
    if (part.empty()) return std::nullopt;
    parts.push_back(std::stod(part));
  }
  double seconds = 0;
  if (parts.size() == 1) seconds = has_days ? parts[0] * 3600 : parts[0] * 60;
  else if (parts.size() == 2) seconds = has_days ? parts[0] * 3600 + parts[1] * 60 : parts[0] * 60 + parts[1];
  else if (parts.size() == 3) seconds = parts[0] * 3600 + parts[1] * 60 + parts[2];
  else return std::nullopt;
  return days * 86400 + seconds;
}

std::string time_text(double seconds) {
  const long minutes = static_cast<long>(std::ceil(seconds / 60));
  return fmt::format("{}:{:02}:00", minutes / 60, minutes % 60);
}

std::string command_failure(const std::string& program, const CommandResult& result) {
  std::string output = result.output;
  while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
  if (result.exit_code == 127)
    return fmt::format("{} not found ({}): --backend slurm runs where the Slurm client commands (sbatch, squeue) "
                       "are on PATH, e.g. a cluster's login node (Debian: apt-get install slurm-client); without "
                       "--backend slurm the sweep runs on this machine",
                       program, output);
  std::string hint;
  if (output.find("Unable to contact slurm controller") != std::string::npos ||
      output.find("Connection refused") != std::string::npos || output.find("Zero Bytes") != std::string::npos ||
      output.find("munge") != std::string::npos || output.find("Could not establish") != std::string::npos)
    hint = "; the Slurm controller does not answer: is the cluster up (`sinfo`)? Does SLURM_CONF name its "
           "slurm.conf? For the single-node test cluster: scripts/slurm-local.sh start, then the export line it prints";
  if (output.find("node configuration is not available") != std::string::npos ||
      output.find("Memory specification") != std::string::npos || output.find("--time") != std::string::npos ||
      output.find("partition") != std::string::npos)
    hint = "; the partition cannot give what the array asks: lower --mem (default: the sweep's `limits: memory_mib`), "
           "--cpus or --time (default: `limits: timeout` + 1 min), or choose another --partition (`sinfo` lists them)";
  return fmt::format("{} failed (exit {}): {}{}", program, result.exit_code, output, hint);
}

}  // namespace medax::slurm
