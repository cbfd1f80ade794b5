// Constant under-relaxation (constant_relaxation.hpp).
#include "fsi/constant_relaxation.hpp"

#include <string>

#include "core/error.hpp"

namespace finverse::fsi {

ConstantRelaxation::ConstantRelaxation(double omega) : omega_(omega) {
  if (!(omega > 0.0 && omega <= 1.0)) {
    throw Error("fsi constant relaxation: expected 0 < omega <= 1, got " + std::to_string(omega));
  }
}

Eigen::VectorXd ConstantRelaxation::accelerate(const Eigen::VectorXd& x_in,
                                               const Eigen::VectorXd& x_out) {
  if (x_in.size() != x_out.size()) {
    throw Error("fsi constant relaxation: expected input and output of equal size, got " +
                std::to_string(x_in.size()) + " and " + std::to_string(x_out.size()));
  }
  return x_in + omega_ * (x_out - x_in);
}

}  // namespace finverse::fsi
