// Constant under-relaxation x_next = x_in + omega (x_out - x_in); omega = 1 is the plain
// (Gauss-Seidel) fixed-point iteration. It converges only when the spectral radius of
// I + omega (H' - I) is below one, which strong added mass (Causin, Gerbeau & Nobile 2005) rules
// out for any practical omega: the baseline the other accelerations are measured against.
#pragma once

#include "fsi/acceleration.hpp"

namespace finverse::fsi {

class ConstantRelaxation final : public Acceleration {
 public:
  explicit ConstantRelaxation(double omega);  // throws unless 0 < omega <= 1

  void reset_time_step() override {}
  [[nodiscard]] Eigen::VectorXd accelerate(const Eigen::VectorXd& x_in,
                                           const Eigen::VectorXd& x_out) override;
  void end_time_step(const Eigen::VectorXd&, const Eigen::VectorXd&) override {}
  [[nodiscard]] double last_omega() const override { return omega_; }
  [[nodiscard]] std::string name() const override { return "constant"; }

 private:
  double omega_;
};

}  // namespace finverse::fsi
