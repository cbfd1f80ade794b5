// Logging, progress and the timing summary (see log.hpp).
#include "core/log.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <mutex>

#include "core/error.hpp"

namespace finverse::log {
namespace {

struct State {
  std::string tool = "finverse";
  Level level = Level::info;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  std::mutex mutex;
};
State& state() {
  static State s;
  return s;
}

void emit(Level level, const char* tag, const std::string& message) {
  auto& s = state();
  if (level < s.level) return;
  std::lock_guard lock(s.mutex);
  std::fprintf(stderr, "[%s %s] %s%s\n", s.tool.c_str(), format_duration(elapsed_seconds()).c_str(), tag, message.c_str());
  std::fflush(stderr);
}

}  // namespace

void set_tool(const std::string& tool) { state().tool = tool; }
const std::string& tool() { return state().tool; }
void set_level(Level level) { state().level = level; }

Level parse_level(const std::string& text) {
  if (text == "debug") return Level::debug;
  if (text == "info") return Level::info;
  if (text == "warn" || text == "warning") return Level::warn;
  if (text == "error") return Level::error;
  if (text == "quiet") return Level::quiet;
  throw Error("--log-level: expected debug, info, warn, error or quiet, got '" + text + "'");
}

void debug(const std::string& m) { emit(Level::debug, "debug: ", m); }
void info(const std::string& m) { emit(Level::info, "", m); }
void warn(const std::string& m) { emit(Level::warn, "warning: ", m); }
void error(const std::string& m) { emit(Level::error, "error: ", m); }

double elapsed_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - state().start).count();
}

std::string format_duration(double s) {
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  return buf;
}

void timing_summary(int threads) {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const double cpu = ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  char buf[160];
  std::snprintf(buf, sizeof buf, "done in %s wall, %s CPU, %d thread%s, peak memory %.0f MB",
                format_duration(elapsed_seconds()).c_str(), format_duration(cpu).c_str(), threads,
                threads == 1 ? "" : "s", ru.ru_maxrss / 1024.0);
  info(buf);
}

Progress::Progress(std::string what, std::size_t total, double cadence_seconds)
    : what_(std::move(what)), total_(total), cadence_(cadence_seconds),
      start_(std::chrono::steady_clock::now()), last_(start_), tty_(isatty(STDERR_FILENO) == 1) {}

std::string Progress::line(std::size_t step, const std::string& status) const {
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string s = what_ + " " + std::to_string(step);
  if (total_ > 0) {
    char pct[32];
    std::snprintf(pct, sizeof pct, "/%zu (%.0f%%)", total_, 100.0 * double(step) / double(total_));
    s += pct;
  }
  if (!status.empty()) s += "  " + status;
  s += "  wall " + format_duration(t);
  if (total_ > 0 && step > 0 && step < total_) s += "  ETA " + format_duration(t * double(total_ - step) / double(step));
  return s;
}

void Progress::update(std::size_t step, const std::string& status) {
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (state().level > Level::info) return;
  if (tty_) {
    if (since < 0.1) return;
    last_ = now;
    std::lock_guard lock(state().mutex);
    std::fprintf(stderr, "\r\033[K[%s] %s", state().tool.c_str(), line(step, status).c_str());
    std::fflush(stderr);
    printed_ = true;
  } else if (since >= cadence_ || !printed_) {
    last_ = now;
    printed_ = true;
    info(line(step, status));
  }
}

void Progress::finish(const std::string& status) {
  if (state().level > Level::info) return;
  if (tty_ && printed_) std::fprintf(stderr, "\r\033[K");
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  info(what_ + " finished in " + format_duration(t) + (status.empty() ? "" : "  " + status));
}

}  // namespace finverse::log
