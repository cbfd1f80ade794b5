// Wall-clock seconds since a steady_clock time point: the one timer of the validation cases and
// benchmarks (their summaries report wall times).
#pragma once

#include <chrono>

namespace finverse {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace finverse
