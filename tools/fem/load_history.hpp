// Tabulated nodal loads f(t_k), k = 0..n-1, interpolated linearly in time (loads.h5, DESIGN.md
// section 4: the hydrodynamic nodal forces from fin-cfd). Before the first sample the load ramps
// linearly from zero at t_0 - ramp to f(t_0), so that a run can start from the unloaded
// reference configuration (ramp = 0: f(t_0) is held); after the last sample f(t_{n-1}) is held.
// The same ramp convention is used for the prescribed root motion (root_motion.hpp).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace finverse::fem {

// Linear interpolation weights on a sample grid with the ramp convention above: value(t) =
// w0 * v[i0] + w1 * v[i1] (i0 == i1 possible; w0 = w1 = 0 before the ramp).
struct SampleWeights {
  int i0 = 0, i1 = 0;
  double w0 = 0, w1 = 0;
};
// Throws InvalidInput unless times are finite and strictly increasing and ramp >= 0.
void check_sample_times(const std::vector<double>& times, double ramp, const char* what);
SampleWeights sample_weights(const std::vector<double>& times, double ramp, double t);

class LoadHistory {
 public:
  LoadHistory() = default;
  // values: one full-length (6 per node) load vector per time. Throws InvalidInput naming the
  // first non-finite entry (time index, node, dof) or inconsistent sizes.
  LoadHistory(std::vector<double> times, std::vector<Eigen::VectorXd> values, double ramp = 0);

  bool empty() const { return times_.empty(); }
  const std::vector<double>& times() const { return times_; }
  double ramp() const { return ramp_; }
  Eigen::VectorXd at(double t) const;  // full length

 private:
  std::vector<double> times_;
  std::vector<Eigen::VectorXd> values_;
  double ramp_ = 0;
};

}  // namespace finverse::fem
