// Logging and progress on stderr (DESIGN.md section 3, "Progress"): leveled one-line messages
// tagged with the tool name and elapsed wall time; a Progress meter that reports step, status
// (simulated time, residual, CFL...), wall time and ETA at a steady cadence, as a live bar only
// when stderr is a terminal; and the one-line timing summary every run ends with.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace finverse::log {

enum class Level { debug = 0, info = 1, warn = 2, error = 3, quiet = 4 };

void set_tool(const std::string& tool);
const std::string& tool();
void set_level(Level level);
Level parse_level(const std::string& text);  // throws finverse::Error on an unknown name

void debug(const std::string& message);
void info(const std::string& message);
void warn(const std::string& message);
void error(const std::string& message);

double elapsed_seconds();           // since the process started logging
std::string format_duration(double seconds);  // "1h02m", "3m05s", "12.3s"

// "fin-cfd: done in 12.3s wall, 23.9s CPU, 2 threads, peak memory 312 MB"
void timing_summary(int threads);

class Progress {
 public:
  // total = number of steps (0 if unknown); cadence = seconds between reports when not a terminal.
  Progress(std::string what, std::size_t total, double cadence_seconds = 5.0);
  // Reports when the cadence has elapsed (or always on a terminal, throttled to 10 Hz).
  void update(std::size_t step, const std::string& status = "");
  void finish(const std::string& status = "");

 private:
  std::string line(std::size_t step, const std::string& status) const;
  std::string what_;
  std::size_t total_;
  double cadence_;
  std::chrono::steady_clock::time_point start_, last_;
  bool tty_;
  bool printed_ = false;
};

}  // namespace finverse::log
