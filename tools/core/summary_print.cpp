// Printing a Summary's metrics (see summary_print.hpp).
#include "core/summary_print.hpp"

#include <ostream>

namespace finverse {

void print_metrics(const Summary& summary, std::ostream& os) {
  for (const auto& m : summary.metrics()) {
    os << "  " << m.name << " = " << m.value;
    if (m.reference) os << " (reference " << *m.reference << ", error " << m.error() << ")";
    if (auto p = m.pass()) os << (*p ? "  pass" : "  MISSED");
    os << "\n";
  }
}

}  // namespace finverse
