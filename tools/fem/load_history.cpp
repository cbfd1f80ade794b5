// Linear interpolation of tabulated nodal loads (see load_history.hpp).
#include "fem/load_history.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/nodal_state.hpp"

namespace finverse::fem {

void check_sample_times(const std::vector<double>& t, double ramp, const char* what) {
  if (t.empty()) throw InvalidInput(std::string(what) + ": no samples");
  for (size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1]))) {
      std::ostringstream os;
      os << what << ": time[" << k << "] = " << t[k] << ", expected finite and strictly increasing";
      throw InvalidInput(os.str());
    }
  }
  if (!std::isfinite(ramp) || ramp < 0)
    throw InvalidInput(std::string(what) + ": ramp " + std::to_string(ramp) + ", expected >= 0");
}

SampleWeights sample_weights(const std::vector<double>& t, double ramp, double x) {
  const int n = static_cast<int>(t.size());
  if (x <= t.front()) {
    if (ramp <= 0 || x >= t.front()) return {0, 0, 1.0, 0.0};
    const double mu = std::clamp((x - (t.front() - ramp)) / ramp, 0.0, 1.0);
    return {0, 0, mu, 0.0};
  }
  if (x >= t.back()) return {n - 1, n - 1, 1.0, 0.0};
  const int i1 = static_cast<int>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  const int i0 = i1 - 1;
  const double w1 = (x - t[i0]) / (t[i1] - t[i0]);
  return {i0, i1, 1.0 - w1, w1};
}

LoadHistory::LoadHistory(std::vector<double> times, std::vector<Eigen::VectorXd> values, double ramp)
    : times_(std::move(times)), values_(std::move(values)), ramp_(ramp) {
  check_sample_times(times_, ramp_, "load history");
  if (values_.size() != times_.size())
    throw InvalidInput("load history: " + std::to_string(values_.size()) + " load vectors for " +
                       std::to_string(times_.size()) + " times");
  for (size_t k = 0; k < values_.size(); ++k) {
    if (values_[k].size() != values_[0].size())
      throw InvalidInput("load history: load vectors of different lengths");
    for (Eigen::Index g = 0; g < values_[k].size(); ++g)
      if (!std::isfinite(values_[k](g))) {
        static const char* names[] = {"fx", "fy", "fz", "mx", "my", "mz"};
        std::ostringstream os;
        os << "load history: load at time index " << k << " (t = " << times_[k] << ") on node "
           << g / kDofsPerNode << " " << names[g % kDofsPerNode] << " is " << values_[k](g)
           << ", expected a finite value";
        throw InvalidInput(os.str());
      }
  }
}

Eigen::VectorXd LoadHistory::at(double t) const {
  const SampleWeights w = sample_weights(times_, ramp_, t);
  Eigen::VectorXd f = w.w0 * values_[w.i0];
  if (w.w1 != 0) f += w.w1 * values_[w.i1];
  return f;
}

}  // namespace finverse::fem
