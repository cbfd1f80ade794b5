// fin-poisson-bench's metrics in the flow solver's benchmark file (poisson_bench_metrics.hpp).
#include "cfd/validation/poisson_bench_metrics.hpp"

#include <string>

namespace finverse::cfd::validation {

nlohmann::json add_poisson_bench_metrics(Summary& cfd, Summary& poisson) {
  for (const Metric& m : poisson.metrics()) {
    const std::string name = "poisson_" + m.name;
    if (m.kind == "max" && m.tolerance)
      cfd.at_most(name, m.value, *m.tolerance, m.source, m.units);
    else
      cfd.info(name, m.value, m.units);
  }
  return poisson.parameters();
}

}  // namespace finverse::cfd::validation
