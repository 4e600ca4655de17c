#pragma once
// Calling the Slurm client commands (sbatch, squeue, sacct) and reading what they print.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace medax::slurm {

struct CommandResult {
  int exit_code = 0;   ///< 127: the program was not found (or could not run)
  std::string output;  ///< stdout and stderr together
};

/// Runs ARGV[0] found on PATH, waits for it and returns its exit code and output.
CommandResult run_command(const std::vector<std::string>& argv);

/// The lines of a command's output, without their line ends, latest last.
std::vector<std::string> lines_of(const std::string& output);

/// Slurm's final states that name why Slurm ended a task (TIMEOUT, OUT_OF_MEMORY, NODE_FAIL...).
bool is_final_state(const std::string& state);

/// The state of each task of ARRAY_ID by array index: squeue while the controller remembers the
/// array (MinJobAge), else sacct when accounting is configured. Empty when neither knows it.
/// `active` is set to the tasks still PENDING/RUNNING/... (not final).
std::map<std::size_t, std::string> array_task_states(const std::string& array_id, std::size_t& active);

/// Slurm's duration text (MINUTES, MINUTES:SECONDS, H:MM:SS, DAYS-H[:MM[:SS]]) in seconds;
/// nullopt for UNLIMITED, NOT_SET or anything else.
std::optional<double> duration_seconds(const std::string& text);

/// Seconds as Slurm's --time text, rounded up to whole minutes (Slurm's granularity): H:MM:00.
std::string time_text(double seconds);

/// The message for a Slurm command that is missing or refused: what happened and what to do.
std::string command_failure(const std::string& program, const CommandResult& result);

}  // namespace medax::slurm
