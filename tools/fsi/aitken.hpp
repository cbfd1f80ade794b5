// Aitken dynamic under-relaxation x_next = x_in + omega_m (x_out - x_in), r = x_out - x_in.
// The seed paper (section 2.3, step 3): omega_m = omega0 = 0.1 for the first three iterations of a
// time level; for m > 3, omega_m = 1 - gamma_m with Mok's form of Aitken's factor
//   gamma_m = gamma_{m-1} + (gamma_{m-1} - 1) (DdX^{m-1} - DdX^m).DdX^m / |DdX^{m-1} - DdX^m|^2,
//   DdX^m = dX^{m-1} - dX^m,  dX^m = X^{N,m} - X^{N-1}.
// Three rules:
//  SeedPaper (default): the formula with DdX^m read as Mok (2001) and Kuettler & Wall (2008) define
//    it, the difference between the relaxed input X^{N,m} and the structure's prediction of the same
//    iteration, i.e. DdX^m = -r_m. This is algebraically Irons-Tuck (omega_m =
//    -omega_{m-1} r_{m-1}.(r_m - r_{m-1}) / |r_m - r_{m-1}|^2) after three fixed iterations.
//  SeedPaperLiteral: the formula applied, as the text's symbols literally say, to the increments of
//    successive relaxed inputs, DdX^m = X^{N,m-1} - X^{N,m} = -omega_{m-1} r_{m-1}: one iteration
//    late, and not a secant of H once two successive omegas differ. Exact for a scalar linear H
//    (tests/unit/fsi/test_aitken.cpp) but on vector problems it stalls: measured not to converge in
//    200 iterations on both test problems (test_linear_fixed_point.cpp, test_added_mass_tube.cpp).
//    Kept to document that finding, not for use.
//  IronsTuck (Kuettler & Wall 2008, preCICE's Aitken): omega_1 = omega0, then the secant above from
//    the second iteration on (fixed_iterations = 1).
// Dot products run over the displacement block X only (the paper's dX) unless displacement_only is
// false; the same omega relaxes X and V (the paper's step 3). omega is bounded to
// omega_min <= |omega| <= omega_max keeping its sign (a zero denominator keeps the previous omega).
// Measured (fsi_tests, mean iterations per step at relative tolerance 1e-6; linear: one step, 1e-8):
// added-mass tube rho_f L/m = 10: SeedPaper 14.2, IronsTuck 12.6; rho_f L/m = 100: 23.4 vs 26.7;
// linear n = 50: 44 vs 43. Neither is consistently faster; IQN-ILS beats both (iqn_ils.hpp).
#pragma once

#include <vector>

#include "fsi/acceleration.hpp"
#include "fsi/coupling_data.hpp"

namespace finverse::fsi {

enum class AitkenRule { SeedPaper, SeedPaperLiteral, IronsTuck };

struct AitkenOptions {
  AitkenRule rule = AitkenRule::SeedPaper;
  double initial_omega = 0.1;    // omega0
  int fixed_iterations = 3;      // Seed rules: iterations per time level with omega = omega0
                                 // (IronsTuck always 1)
  double omega_min = 1e-6;       // bounds on |omega|
  double omega_max = 1.0;
  bool displacement_only = true; // Aitken factor from the X block only
  bool reuse_last_omega = false; // IronsTuck: start a time step from the last step's omega
};

class AitkenRelaxation final : public Acceleration {
 public:
  AitkenRelaxation(InterfaceLayout layout, AitkenOptions options = {});

  void reset_time_step() override;
  [[nodiscard]] Eigen::VectorXd accelerate(const Eigen::VectorXd& x_in,
                                           const Eigen::VectorXd& x_out) override;
  void end_time_step(const Eigen::VectorXd&, const Eigen::VectorXd&) override {}
  [[nodiscard]] double last_omega() const override { return omega_; }
  [[nodiscard]] std::string name() const override;
  // The last omega (a time step starts from it with reuse_last_omega).
  [[nodiscard]] CarriedState carried_state() const override { return {{"aitken_omega", {omega_}}}; }
  void restore_carried_state(const CarriedState& state) override;

 private:
  double bounded(double omega) const;
  double mok_omega(const Eigen::VectorXd& dd_now);
  double irons_tuck_omega(const Eigen::VectorXd& residual);

  InterfaceLayout layout_;
  AitkenOptions options_;
  int iteration_ = 0;            // iterations of this time step so far (1-based after accelerate)
  double omega_;                 // omega of the last update
  Eigen::VectorXd previous_in_;  // SeedPaperLiteral: X^{N,m-1}
  Eigen::VectorXd previous_dd_;  // Seed rules: DdX^{m-1}
  Eigen::VectorXd previous_residual_;  // IronsTuck: r_{k-1}
};

}  // namespace finverse::fsi
