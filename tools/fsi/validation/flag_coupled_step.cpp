// The structure's side of a Turek-Hron coupled evaluation; see flag_coupled_step.hpp.
#include "fsi/validation/flag_coupled_step.hpp"

namespace finverse::fsi::validation {

Eigen::VectorXd FlagCoupledStep::advance_structure(fem::CoupledStructure& structure, double t_new,
                                                   const Eigen::Matrix2Xd& loads, const Eigen::Matrix2Xd& reference,
                                                   fem::CoupledStepReport& report) const {
  const Eigen::Index n = reference.cols();
  const Eigen::VectorXd load = Eigen::Map<const Eigen::VectorXd>(loads.data(), 2 * n);
  try {
    report = structure.advance(t_new, load);
  } catch (const std::exception& e) {
    throw Error(where() + ": structure: " + e.what());
  }
  Eigen::VectorXd out(4 * n);
  out.head(2 * n) = structure.wet_positions() - Eigen::Map<const Eigen::VectorXd>(reference.data(), 2 * n);
  out.tail(2 * n) = structure.wet_velocities();
  return out;
}

}  // namespace finverse::fsi::validation
