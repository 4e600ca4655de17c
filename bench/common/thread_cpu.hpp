#pragma once
// CPU time of each thread of this process (Linux: /proc/self/task/<tid>/stat), to estimate what
// a parallel run would take on an idle machine: the busiest thread's CPU time. On a shared,
// loaded machine the wall time mostly measures the other processes; this does not (spinning
// waits count as busy, so it is an upper bound of the idle-machine wall time of the parallel parts).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unistd.h>

namespace medax::bench {

/// Seconds of CPU (user + system) used so far by each live thread, by thread id.
inline std::map<long, double> thread_cpu_seconds() {
  std::map<long, double> out;
  const double tick = static_cast<double>(sysconf(_SC_CLK_TCK));
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream in(entry.path() / "stat");
    std::string line;
    if (!std::getline(in, line)) continue;
    // Fields after the command name (in parentheses, may contain spaces): state is field 3,
    // utime field 14, stime field 15.
    std::istringstream rest(line.substr(line.rfind(')') + 2));
    std::string field;
    double utime = 0, stime = 0;
    for (int k = 3; k <= 15 && rest >> field; ++k) {
      if (k == 14) utime = std::stod(field);
      if (k == 15) stime = std::stod(field);
    }
    out[std::stol(entry.path().filename().string())] = (utime + stime) / tick;
  }
  return out;
}

/// The largest CPU time any one thread spent between the two readings.
inline double busiest_thread_seconds(const std::map<long, double>& before, const std::map<long, double>& after) {
  double busiest = 0;
  for (const auto& [tid, seconds] : after) {
    const auto it = before.find(tid);
    busiest = std::max(busiest, seconds - (it == before.end() ? 0.0 : it->second));
  }
  return busiest;
}

}  // namespace medax::bench
