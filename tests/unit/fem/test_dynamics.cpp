// Dynamics and modal analysis: generalized-alpha parameters and energy behaviour, eigen
// frequencies against Euler-Bernoulli (dense and subspace paths), spectral peak picking.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/modal.hpp"
#include "fem/spectral_peaks.hpp"
#include "fem/validation/cases.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;
using finverse::fem::test::cantilever;

TEST(GeneralizedAlpha, ChungHulbertParameters) {
  Model m = cantilever(2, 1.0, 1e9, 0.01, 0.002, 0.01, 0.002);
  GeneralizedAlpha trapezoidal(m, DynamicOptions{.time_step = 1e-3, .spectral_radius = 1.0});
  EXPECT_DOUBLE_EQ(trapezoidal.alpha_m(), 0.5);
  EXPECT_DOUBLE_EQ(trapezoidal.alpha_f(), 0.5);
  EXPECT_DOUBLE_EQ(trapezoidal.beta(), 0.25);
  EXPECT_DOUBLE_EQ(trapezoidal.gamma(), 0.5);
  GeneralizedAlpha damped(m, DynamicOptions{.time_step = 1e-3, .spectral_radius = 0.8});
  EXPECT_NEAR(damped.alpha_m(), 0.6 / 1.8, 1e-15);
  EXPECT_NEAR(damped.alpha_f(), 0.8 / 1.8, 1e-15);
  EXPECT_THROW(GeneralizedAlpha(m, DynamicOptions{.time_step = 0}), InvalidInput);
}

namespace {
// Relative energy change after `steps` steps of a cantilever released with a tip velocity.
double energy_change(double rho_inf, int steps) {
  Model m = cantilever(6, 0.5, 2e9, 0.01, 0.002, 0.01, 0.002, 1100);
  DynamicOptions o;
  o.time_step = 2e-4;
  o.spectral_radius = rho_inf;
  GeneralizedAlpha ga(m, o);
  DynamicState s = ga.reference_state();
  s.velocity(6 * 6 + 2) = 0.01;
  ga.initialize(s);
  const double e0 = ga.kinetic_energy(s) + ga.strain_energy(s);
  for (int k = 0; k < steps; ++k) ga.step(s);
  return (ga.kinetic_energy(s) + ga.strain_energy(s) - e0) / e0;
}
}  // namespace

TEST(GeneralizedAlpha, UndampedConservesEnergyAndDissipativeVariantLoses) {
  EXPECT_LT(std::abs(energy_change(1.0, 400)), 1e-6);
  EXPECT_LT(energy_change(0.5, 400), -1e-3);  // the measure can fail: numerical dissipation shows
}

// Issue 45, deliverable 2: the full-Newton variant (no constant-acceleration predictor, a new
// factorisation every iteration) changes the iteration's path, not the equations: the same
// converged states on a vibrating cantilever, with more iterations.
TEST(GeneralizedAlpha, FullNewtonVariantConvergesToTheSameStates) {
  Model m = cantilever(6, 0.5, 2e9, 0.01, 0.002, 0.01, 0.002, 1100);
  DynamicOptions o;
  o.time_step = 2e-4;
  o.spectral_radius = 0.5;
  DynamicOptions full = o;
  full.predict_with_acceleration = false;
  full.modified_newton = false;
  GeneralizedAlpha a(m, o), b(m, full);
  DynamicState sa = a.reference_state();
  sa.velocity(6 * 6 + 2) = 0.05;
  DynamicState sb = sa;
  a.initialize(sa);
  b.initialize(sb);
  int ia = 0, ib = 0;
  for (int k = 0; k < 100; ++k) {
    ia += a.step(sa).iterations;
    ib += b.step(sb).iterations;
  }
  const double scale = sa.velocity.norm();
  EXPECT_LT((sa.velocity - sb.velocity).norm(), 1e-7 * scale);
  for (size_t n = 0; n < sa.configuration.position.size(); ++n)
    EXPECT_LT((sa.configuration.position[n] - sb.configuration.position[n]).norm(), 1e-10);
  EXPECT_GT(ib, ia);  // the predictor saves iterations where the motion is smooth
}

TEST(GeneralizedAlpha, RayleighDampingDecaysAtTheExpectedRate) {
  // Mass-proportional damping a_M gives zeta_1 = a_M / (2 omega_1): the energy of a first-mode
  // vibration decays like exp(-a_M t).
  Model m = cantilever(8, 0.5, 2e9, 0.01, 0.002, 0.01, 0.002, 1100);
  const ModalResult modes = modal_analysis(m, m.reference_state(), ModalOptions{.modes = 1});
  const double T1 = 2 * std::numbers::pi / modes.omega(0);
  DynamicOptions o;
  o.time_step = T1 / 200;
  o.rayleigh_mass = 2.0;
  GeneralizedAlpha ga(m, o);
  DynamicState s = ga.reference_state();
  s.velocity = 1e-2 * modes.shapes.col(0);  // pure first mode
  ga.initialize(s);
  const double e0 = ga.kinetic_energy(s) + ga.strain_energy(s);
  for (int k = 0; k < 1000; ++k) ga.step(s);  // 5 periods
  const double e1 = ga.kinetic_energy(s) + ga.strain_energy(s);
  EXPECT_NEAR(std::log(e1 / e0) / (-o.rayleigh_mass * s.time), 1.0, 0.02);
}

TEST(Modal, CantileverFrequenciesMatchEulerBernoulliAndBothSolversAgree) {
  const double L = 0.3, E = 1e9, b = 0.01, t = 0.001, rho = 1100;
  Model m = cantilever(16, L, E, b, t, b, t, rho);
  ModalOptions o;
  o.modes = 8;
  const ModalResult dense = modal_analysis(m, m.reference_state(), o);
  o.force_subspace = true;
  const ModalResult sub = modal_analysis(m, m.reference_state(), o);
  EXPECT_GT(sub.iterations, 1);
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(sub.omega(k), dense.omega(k), 1e-7 * dense.omega(k));
  // The lowest mode bends about the thin direction.
  const double EI = E * b * t * t * t / 12;
  const double beta = finverse::fem::validation::cantilever_beta_l(1);
  const double omega1 = beta * beta / (L * L) * std::sqrt(EI / (rho * b * t));
  EXPECT_NEAR(dense.omega(0), omega1, 1e-4 * omega1);
}

TEST(Modal, EulerBernoulliRootsMatchTabulatedValues) {
  using finverse::fem::validation::cantilever_beta_l;
  EXPECT_NEAR(cantilever_beta_l(1), 1.87510407, 1e-8);
  EXPECT_NEAR(cantilever_beta_l(2), 4.69409113, 1e-8);
  EXPECT_NEAR(cantilever_beta_l(3), 7.85475744, 1e-8);
}

TEST(SpectralPeaks, RecoversTheFrequenciesOfASumOfSinusoids) {
  const double dt = 1e-3;
  std::vector<double> x(5000);
  for (size_t i = 0; i < x.size(); ++i) {
    const double t = dt * static_cast<double>(i);
    x[i] = std::sin(2 * std::numbers::pi * 3.3 * t) + 0.6 * std::cos(2 * std::numbers::pi * 21.7 * t) +
           0.4 * std::sin(2 * std::numbers::pi * 61.05 * t + 0.3) + 0.5;
  }
  const auto peaks = spectral_peaks(x, dt, 3);
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_NEAR(peaks[0].frequency, 3.3, 3.3 * 2e-3);
  EXPECT_NEAR(peaks[1].frequency, 21.7, 21.7 * 1e-3);
  EXPECT_NEAR(peaks[2].frequency, 61.05, 61.05 * 1e-3);
}
