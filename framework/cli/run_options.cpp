// The options of `medax run` beyond those it shares with `validate`.
#include "commands.hpp"

#include <CLI/CLI.hpp>

namespace medax::cli {

void add_run_options(CLI::App& run, RunArgs& args) {
  run.add_option("--out,-o", args.out, "Run folder (default: medax-runs/<pipeline>-<input>)");
  run.add_flag("--quiet,-q", args.quiet, "Only errors on the terminal (log.txt has everything)");
  run.add_option("--jobs,-j", args.parallel_jobs, "Sweeps: jobs run in parallel, each in its own process")
      ->check(CLI::PositiveNumber);
  run.add_option("--timeout", args.timeout, "Sweeps: seconds per job before it is killed (overrides `limits:`)");
  run.add_option("--memory-mib", args.memory_mib, "Sweeps: address-space limit per job (overrides `limits:`)");
  run.add_flag("--results-only", args.results_only,
               "Sweeps: rewrite results.csv/md and plots from the job folders (after editing `table:` or `plots:`)");
  run.add_flag("--job", args.single_job, "Run as one job of a sweep (used by the sweep runner)")->group("");
}

}  // namespace medax::cli
