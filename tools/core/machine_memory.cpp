// Whether a run fits in this machine's memory (see machine_memory.hpp).
#include "core/machine_memory.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace finverse {

std::uint64_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(size) : 0;
}

void require_memory(double bytes, const std::string& what) {
  const double machine = static_cast<double>(physical_memory_bytes());
  if (std::isfinite(bytes) && (machine <= 0 || bytes <= 0.8 * machine)) return;
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  char estimate[64], have[64];
  if (std::isfinite(bytes) && bytes < 1e6 * kGiB)
    std::snprintf(estimate, sizeof estimate, "about %.3g GiB", bytes / kGiB);
  else
    std::snprintf(estimate, sizeof estimate, "more than a million GiB");
  std::snprintf(have, sizeof have, "%.3g GiB", machine / kGiB);
  throw Error(what + ": needs " + estimate + ", more than the " + have + " of this machine");
}

}  // namespace finverse
