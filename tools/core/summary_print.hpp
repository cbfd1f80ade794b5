// The metrics of a Summary as the executables print them on stderr after writing summary.json:
// one line each, "  name = value (reference r, error e)  pass|MISSED".
#pragma once

#include <iosfwd>

#include "core/summary.hpp"

namespace finverse {

void print_metrics(const Summary& summary, std::ostream& os);

}  // namespace finverse
