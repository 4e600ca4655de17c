#include "run_context.hpp"

#include <medax/io.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <signal.h>
#include <cstdio>

namespace medax::detail {

namespace {
std::atomic<int> g_signal{0};  // the first SIGINT/SIGTERM received, 0 if none
static_assert(std::atomic<int>::is_always_lock_free, "read and written in a signal handler");

extern "C" void on_interrupt(int sig) {
  if (g_signal.exchange(sig) != 0) std::_Exit(128 + sig);  // a second signal: stop now
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
}  // namespace

std::uint64_t stage_seed(std::uint64_t pipeline_seed, const std::string& stage_id) {
  std::uint64_t h = 0xCBF29CE484222325ull;  // FNV-1a of the id
  for (unsigned char c : stage_id) h = (h ^ c) * 0x100000001B3ull;
  return splitmix64(pipeline_seed ^ splitmix64(h));
}

void install_interrupt_handler() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}
bool interrupt_requested() { return g_signal.load(std::memory_order_relaxed) != 0; }
int interrupt_signal() { return g_signal.load(std::memory_order_relaxed); }

std::string signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT (Ctrl-C)";
    case SIGTERM: return "SIGTERM";
    default: return fmt::format("signal {}", sig);
  }
}

RunContext::RunContext(std::shared_ptr<spdlog::logger> logger, std::string stage_id, std::uint64_t seed,
                       std::filesystem::path out_dir, SceneData& data)
    : logger_(std::move(logger)),
      stage_id_(std::move(stage_id)),
      seed_(seed),
      rng_(seed),
      out_dir_(std::move(out_dir)),
      last_progress_(std::chrono::steady_clock::now()),
      terminal_(::isatty(STDERR_FILENO) != 0),
      data_(data) {}

RunContext::~RunContext() {
  if (progress_shown_ && terminal_) std::fprintf(stderr, "\r\033[K");
}

void RunContext::info(std::string_view message) { logger_->info("[{}] {}", stage_id_, message); }
void RunContext::warn(std::string_view message) { logger_->warn("[{}] {}", stage_id_, message); }

void RunContext::progress(double fraction, std::string_view what) {
  const auto now = std::chrono::steady_clock::now();
  // On a terminal, redraw one line a few times a second; in a log, one line every 10 s.
  const auto period = terminal_ ? std::chrono::milliseconds(250) : std::chrono::milliseconds(10000);
  if (now - last_progress_ < period) return;  // also hides work that ends within one period
  last_progress_ = now;
  progress_shown_ = true;
  const int percent = static_cast<int>(100.0 * std::clamp(fraction, 0.0, 1.0));
  if (terminal_) std::fprintf(stderr, "\r\033[K[%s] %3d%% %.*s", stage_id_.c_str(), percent,
                              static_cast<int>(what.size()), what.data());
  else logger_->info("[{}] {}% {}", stage_id_, percent, what);
}

std::filesystem::path RunContext::write_output(const std::string& name,
                                               const std::function<void(std::ostream&)>& body) {
  const std::filesystem::path path = out_dir_ / name;
  write_file_atomic(path, body);
  logger_->info("[{}] wrote {}", stage_id_, path.filename().string());
  return path;
}

}  // namespace medax::detail
