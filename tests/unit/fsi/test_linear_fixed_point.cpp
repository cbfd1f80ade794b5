// Test (a) of the coupling core: the linear fixed point x = A x + b, n = 50, A symmetric with
// eigenvalues evenly in [-3, 0.5] (spectral radius 3, the sign of added mass: plain Gauss-Seidel
// diverges), solved by the coupling loop (implicit_coupling.hpp) with each acceleration.
// Constant relaxation is reported as diverged; Aitken (both rules) converges; IQN-ILS converges
// in <= n + 1 iterations; over a sequence of steps with slowly changing b, reuse of past steps'
// columns lowers the mean iterations per step. Measured counts are printed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fsi/aitken.hpp"
#include "fsi/constant_relaxation.hpp"
#include "fsi/iqn_ils.hpp"
#include "linear_step.hpp"

namespace finverse::fsi {
namespace {

constexpr int kN = 50;

struct Problem {
  Eigen::MatrixXd a = test::symmetric_with_spectrum(kN, -3.0, 0.5, 2024);
  Eigen::VectorXd b0 = test::random_vector(kN, 1);
  Eigen::VectorXd b1 = test::random_vector(kN, 2);
  // b of step N: slowly changing
  [[nodiscard]] Eigen::VectorXd b(long step) const {
    return b0 + std::sin(0.05 * static_cast<double>(step)) * b1;
  }
};

CouplingOptions linear_options(double tolerance = 1e-8, int cap = 200) {
  CouplingOptions options;
  options.convergence.relative_tolerance = tolerance;
  options.convergence.absolute_tolerance = 1e-14;
  options.max_iterations = cap;
  options.predictor = Predictor::Constant;
  return options;
}

// One step from x = 0; the iterations, or -1 when the loop reported divergence.
int one_step(std::unique_ptr<Acceleration> acceleration, const Problem& p, std::string* error) {
  test::LinearStep step(p.a, p.b(1));
  ImplicitCoupling coupling({kN, 0}, Eigen::VectorXd::Zero(kN), std::move(acceleration),
                            linear_options());
  try {
    const StepStatistics stats = coupling.advance(step, 0.1);
    EXPECT_LT((coupling.state() - step.solution()).norm(), 1e-6 * step.solution().norm());
    return stats.iterations;
  } catch (const Error& e) {  // CouplingDiverged or CouplingNotConverged
    if (error) *error = e.what();
    return -1;
  }
}

TEST(LinearFixedPoint, ConstantRelaxationDivergesAitkenAndIqnConverge) {
  const Problem p;
  std::string error;
  EXPECT_EQ(one_step(std::make_unique<ConstantRelaxation>(1.0), p, &error), -1);
  std::printf("[ linear  ] constant omega = 1: %s\n", error.c_str());
  EXPECT_NE(error.find("coupling diverged at step 1 (time 0.1): residual"), std::string::npos);
  // omega = 0.6: eigenvalues of I + omega (A - I) reach 1 - 0.6 * 4 = -1.4: diverges too.
  EXPECT_EQ(one_step(std::make_unique<ConstantRelaxation>(0.6), p, &error), -1);

  const int seed = one_step(std::make_unique<AitkenRelaxation>(InterfaceLayout{kN, 0}), p, nullptr);
  AitkenOptions it;
  it.rule = AitkenRule::IronsTuck;
  const int irons =
      one_step(std::make_unique<AitkenRelaxation>(InterfaceLayout{kN, 0}, it), p, nullptr);
  AitkenOptions literal;
  literal.rule = AitkenRule::SeedPaperLiteral;
  std::string literal_error;
  const int lit = one_step(std::make_unique<AitkenRelaxation>(InterfaceLayout{kN, 0}, literal), p,
                           &literal_error);
  const int iqn = one_step(std::make_unique<IqnIls>(InterfaceLayout{kN, 0}), p, nullptr);
  IqnIlsOptions unfiltered;
  unfiltered.filter_epsilon = 0.0;
  const int iqn_nf =
      one_step(std::make_unique<IqnIls>(InterfaceLayout{kN, 0}, unfiltered), p, nullptr);
  std::printf("[ linear  ] n = %d, rho(A) = 3, rel. tol 1e-8, iterations: Aitken seed rule %d, "
              "Aitken Irons-Tuck %d, IQN-ILS %d (filter off %d)\n",
              kN, seed, irons, iqn, iqn_nf);
  std::printf("[ linear  ] Aitken, the seed's formula on relaxed-input increments: %s\n",
              lit > 0 ? std::to_string(lit).c_str() : literal_error.c_str());
  EXPECT_GT(seed, 0);
  EXPECT_GT(irons, 0);
  EXPECT_GT(iqn, 0);
  EXPECT_LE(iqn, kN + 1);
  EXPECT_LE(iqn_nf, kN + 1);
  EXPECT_LT(iqn, std::min(seed, irons));
}

TEST(LinearFixedPoint, ReuseOfPastStepsLowersMeanIterations) {
  const Problem p;
  const int steps = 20;
  std::printf("[ linear  ] %d steps, b slowly changing, IQN-ILS mean (max) iterations per step:\n",
              steps);
  double mean_q0 = 0.0, mean_q8 = 0.0;
  for (int q : {0, 1, 2, 4, 8, 16}) {
    IqnIlsOptions options;
    options.reused_time_steps = q;
    test::LinearStep step(p.a, p.b(1));
    ImplicitCoupling coupling({kN, 0}, Eigen::VectorXd::Zero(kN),
                              std::make_unique<IqnIls>(InterfaceLayout{kN, 0}, options),
                              linear_options());
    int total = 0, most = 0;
    for (long n = 1; n <= steps; ++n) {
      step.set_b(p.b(n));
      const StepStatistics stats = coupling.advance(step, 0.1);
      EXPECT_LT((coupling.state() - step.solution()).norm(), 1e-6 * step.solution().norm());
      total += stats.iterations;
      most = std::max(most, stats.iterations);
    }
    const double mean = static_cast<double>(total) / steps;
    std::printf("[ linear  ]   q = %2d: %.2f (%d)\n", q, mean, most);
    if (q == 0) mean_q0 = mean;
    if (q == 8) mean_q8 = mean;
  }
  EXPECT_LT(mean_q8, 0.5 * mean_q0);
}

}  // namespace
}  // namespace finverse::fsi
