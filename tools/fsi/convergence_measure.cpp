// The coupling's relative convergence measure with an absolute floor (convergence_measure.hpp).
#include "fsi/convergence_measure.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::fsi {

ConvergenceMeasure::ConvergenceMeasure(InterfaceLayout layout, ConvergenceOptions options)
    : layout_(layout), options_(options) {
  layout_.validate();
  if (!(options_.relative_tolerance >= 0.0) || !(options_.absolute_tolerance >= 0.0) ||
      (options_.relative_tolerance == 0.0 && options_.absolute_tolerance == 0.0)) {
    throw Error("fsi convergence: expected non-negative tolerances, not both zero, got relative " +
                std::to_string(options_.relative_tolerance) + " and absolute " +
                std::to_string(options_.absolute_tolerance));
  }
}

void ConvergenceMeasure::reset() {
  absolute_.clear();
  relative_.clear();
}

bool ConvergenceMeasure::measure(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) {
  layout_.check(x_in, "convergence measure input");
  if (x_out.size() != layout_.size()) layout_.check(x_out, "convergence measure output");
  const Eigen::Index n = options_.displacement_only ? layout_.n_position : layout_.size();
  // A non-finite output is measured (as inf/NaN) rather than rejected: the loop turns it into a
  // divergence error that names the step.
  const double diff = (x_out.head(n) - x_in.head(n)).norm();
  const double ref = x_out.head(n).norm();
  const double rel = ref > 0.0 ? diff / ref : diff;
  absolute_.push_back(diff);
  relative_.push_back(rel);
  return std::isfinite(diff) &&
         (diff <= options_.absolute_tolerance || diff <= options_.relative_tolerance * ref);
}

}  // namespace finverse::fsi
