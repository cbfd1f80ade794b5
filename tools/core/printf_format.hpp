// One number formatted with a printf format ("%.3g"): the log lines and summary notes of the
// validation cases print their numbers this way.
#pragma once

#include <cstdio>
#include <string>

namespace finverse {

inline std::string printf_format(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

}  // namespace finverse
