// Convergence of one time step's coupling iterations: the relative measure
//   |x_out - x_in| / |x_out|   (x_out = S(F(x_in)), the structure's output for the input x_in)
// as preCICE's relative-convergence measure, with an absolute floor for a surface at rest.
// By default only the displacement block X is measured, as the paper's stop test
// |X^{N,m+1} - X^{N,m}| <= eps (section 2.3, step 5). Note the paper measures the relaxed update
// (omega times the residual), which is looser by the factor omega; we measure the residual itself.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fsi/coupling_data.hpp"

namespace finverse::fsi {

struct ConvergenceOptions {
  double relative_tolerance = 1e-5;   // on |x_out - x_in| / |x_out|
  double absolute_tolerance = 1e-12;  // converged also when |x_out - x_in| <= this
  bool displacement_only = true;      // measure X only (the paper); false: all of [X; V]
};

class ConvergenceMeasure {
 public:
  ConvergenceMeasure(InterfaceLayout layout, ConvergenceOptions options);

  // Forget the residual history (start of a time step).
  void reset();
  // Measure one iteration, append it to the history; true when converged.
  bool measure(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out);

  // Of the last measure(): |x_out - x_in| and the relative value (|x_out - x_in| when |x_out| = 0).
  [[nodiscard]] double absolute() const { return absolute_.empty() ? 0.0 : absolute_.back(); }
  [[nodiscard]] double relative() const { return relative_.empty() ? 0.0 : relative_.back(); }
  [[nodiscard]] const std::vector<double>& absolute_history() const { return absolute_; }
  [[nodiscard]] const std::vector<double>& relative_history() const { return relative_; }
  [[nodiscard]] const ConvergenceOptions& options() const { return options_; }

 private:
  InterfaceLayout layout_;
  ConvergenceOptions options_;
  std::vector<double> absolute_;
  std::vector<double> relative_;
};

}  // namespace finverse::fsi
