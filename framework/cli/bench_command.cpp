// `medax bench`: repeatable timing of a pipeline, per stage.
#include "commands.hpp"

#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <map>

namespace medax::cli {

int bench(const BenchArgs& args) {
  if (!check_pipeline_file(args.pipeline)) return 2;
  Registry& registry = Registry::global();
  PipelineConfig config;
  try {
    config = load_pipeline(args.pipeline, registry, Overrides{args.input, args.settings});
  } catch (const PipelineError& e) {
    for (const Diagnostic& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.format());
    return 2;
  }
  const auto scratch = std::filesystem::temp_directory_path() / fmt::format("medax-bench-{}", ::getpid());
  std::map<std::string, std::vector<double>> seconds;  // by stage id
  std::vector<std::string> order;
  for (int run = 0; run < args.warmup + args.repeat; ++run) {
    std::filesystem::remove_all(scratch);
    const RunResult result = run_pipeline(config, RunOptions{scratch, true});
    if (!result.ok) {
      fmt::print(stderr, "error: {}\n", result.error);
      std::error_code ec;
      std::filesystem::remove_all(scratch, ec);
      return failed_run_exit_code(result.signal);
    }
    const bool timed = run >= args.warmup;
    fmt::print(stderr, "{} {}/{}\n", timed ? "run" : "warm-up", timed ? run - args.warmup + 1 : run + 1,
               timed ? args.repeat : args.warmup);
    if (!timed) continue;
    for (const StageTiming& t : result.timings) {
      if (!seconds.count(t.id)) order.push_back(t.id);
      seconds[t.id].push_back(t.seconds);
    }
  }
  std::filesystem::remove_all(scratch);
  fmt::print("{} on {} ({} runs after {} warm-up)\n", config.name, config.input.filename().string(), args.repeat,
             args.warmup);
  fmt::print("{:<24} {:>12} {:>12}\n", "stage", "min (s)", "median (s)");
  for (const std::string& id : order) {
    std::vector<double>& v = seconds[id];
    std::sort(v.begin(), v.end());
    fmt::print("{:<24} {:>12.4f} {:>12.4f}\n", id, v.front(), v[v.size() / 2]);
  }
  return 0;
}

}  // namespace medax::cli
