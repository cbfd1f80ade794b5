// Mean and peak of a force coefficient over a record (see force_statistics.hpp; Fig. 16).
#include "report/force_statistics.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace finverse::report {

ForceStatistics force_statistics(const std::vector<double>& time, const std::vector<double>& c) {
  if (c.empty() || time.size() != c.size())
    throw Error("force statistics: expected a non-empty coefficient series with one time per sample");
  ForceStatistics s;
  s.peak = *std::max_element(c.begin(), c.end());
  s.minimum = *std::min_element(c.begin(), c.end());
  const double span = time.back() - time.front();
  if (c.size() == 1 || !(span > 0)) {
    double sum = 0;
    for (double v : c) sum += v;
    s.mean = sum / static_cast<double>(c.size());
    return s;
  }
  double integral = 0;
  for (std::size_t i = 1; i < c.size(); ++i) {
    if (time[i] < time[i - 1]) throw Error("force statistics: the times are not ascending");
    integral += 0.5 * (c[i] + c[i - 1]) * (time[i] - time[i - 1]);
  }
  s.mean = integral / span;
  return s;
}

}  // namespace finverse::report
