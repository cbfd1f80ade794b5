// Aitken relaxation (aitken.hpp) against hand-computed iterates: on a scalar linear map
// H(x) = a x + b both rules find omega = 1 / (1 - a) exactly, the seed paper's rule after its three
// fixed iterations with omega0 (so x^5 is the fixed point), Irons-Tuck after one secant (x^3).
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "fsi/aitken.hpp"
#include "fsi/constant_relaxation.hpp"

namespace finverse::fsi {
namespace {

constexpr double kA = -3.0;  // plain iteration diverges (|a| > 1)
constexpr double kB = 2.0;
constexpr double kFixed = kB / (1.0 - kA);

Eigen::VectorXd h(const Eigen::VectorXd& x) { return (kA * x.array() + kB).matrix(); }

TEST(Aitken, SeedPaperRuleIsExactAfterThreeFixedIterations) {
  AitkenRelaxation aitken({1, 0});  // defaults: the paper's rule, omega0 = 0.1, three iterations
  aitken.reset_time_step();
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.0);
  std::vector<double> omegas;
  for (int m = 1; m <= 4; ++m) {
    x = aitken.accelerate(x, h(x));
    omegas.push_back(aitken.last_omega());
  }
  EXPECT_DOUBLE_EQ(omegas[0], 0.1);
  EXPECT_DOUBLE_EQ(omegas[1], 0.1);
  EXPECT_DOUBLE_EQ(omegas[2], 0.1);
  EXPECT_NEAR(omegas[3], 1.0 / (1.0 - kA), 1e-14);
  EXPECT_NEAR(x(0), kFixed, 1e-14);
  // A new time level starts again from omega0.
  aitken.reset_time_step();
  (void)aitken.accelerate(x, h(x));
  EXPECT_DOUBLE_EQ(aitken.last_omega(), 0.1);
}

TEST(Aitken, LiteralSeedRuleIsExactOnScalarAfterThreeFixedIterations) {
  AitkenOptions options;
  options.rule = AitkenRule::SeedPaperLiteral;
  AitkenRelaxation aitken({1, 0}, options);
  aitken.reset_time_step();
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.0);
  for (int m = 1; m <= 4; ++m) x = aitken.accelerate(x, h(x));
  EXPECT_NEAR(aitken.last_omega(), 0.25, 1e-14);
  EXPECT_NEAR(x(0), kFixed, 1e-14);
}

TEST(Aitken, SeedRuleIsIronsTuckAfterItsFixedIterations) {
  // Mok's gamma form of the paper equals the omega form of Irons-Tuck: with one fixed iteration the
  // two give the same omegas on a vector problem, to round-off.
  Eigen::MatrixXd a(3, 3);
  a << -2.0, 0.3, 0.1, 0.2, -1.0, 0.4, 0.0, 0.5, 0.3;
  const Eigen::Vector3d b(1.0, -2.0, 0.5);
  AitkenOptions seed_options;
  seed_options.fixed_iterations = 1;
  AitkenOptions it_options;
  it_options.rule = AitkenRule::IronsTuck;
  AitkenRelaxation seed({3, 0}, seed_options), irons({3, 0}, it_options);
  seed.reset_time_step();
  irons.reset_time_step();
  Eigen::VectorXd x1 = Eigen::Vector3d::Zero(), x2 = x1;
  for (int m = 1; m <= 8; ++m) {
    x1 = seed.accelerate(x1, a * x1 + b);
    x2 = irons.accelerate(x2, a * x2 + b);
    EXPECT_NEAR(seed.last_omega(), irons.last_omega(), 1e-12 * std::abs(irons.last_omega()));
  }
  EXPECT_LT((x1 - x2).norm(), 1e-12);
}

TEST(Aitken, IronsTuckIsExactAfterOneSecant) {
  AitkenOptions options;
  options.rule = AitkenRule::IronsTuck;
  AitkenRelaxation aitken({1, 0}, options);
  aitken.reset_time_step();
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.0);
  x = aitken.accelerate(x, h(x));
  EXPECT_DOUBLE_EQ(aitken.last_omega(), 0.1);
  x = aitken.accelerate(x, h(x));
  EXPECT_NEAR(aitken.last_omega(), 0.25, 1e-14);
  EXPECT_NEAR(x(0), kFixed, 1e-14);
}

TEST(Aitken, FactorFromDisplacementBlockRelaxesBoth) {
  // [X; V] with V = 10 X: the factor comes from X, the same omega relaxes V (paper, step 3).
  AitkenRelaxation aitken({1, 1});
  aitken.reset_time_step();
  Eigen::VectorXd x(2);
  x << 1.0, 10.0;
  auto hv = [](const Eigen::VectorXd& z) {
    Eigen::VectorXd out(2);
    out(0) = kA * z(0) + kB;
    out(1) = 10.0 * out(0);
    return out;
  };
  for (int m = 1; m <= 4; ++m) x = aitken.accelerate(x, hv(x));
  EXPECT_NEAR(x(0), kFixed, 1e-13);
  EXPECT_NEAR(x(1), 10.0 * kFixed, 1e-12);
}

TEST(Aitken, OmegaIsBoundedAndInputsChecked) {
  AitkenOptions options;
  options.rule = AitkenRule::IronsTuck;
  options.omega_max = 0.2;  // the exact 0.25 is clipped
  AitkenRelaxation aitken({1, 0}, options);
  aitken.reset_time_step();
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.0);
  x = aitken.accelerate(x, h(x));
  x = aitken.accelerate(x, h(x));
  EXPECT_DOUBLE_EQ(aitken.last_omega(), 0.2);
  EXPECT_THROW((void)aitken.accelerate(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2)), Error);
  options.initial_omega = 0.5;  // above omega_max
  EXPECT_THROW(AitkenRelaxation({1, 0}, options), Error);
  EXPECT_THROW(ConstantRelaxation(0.0), Error);
  EXPECT_THROW(ConstantRelaxation(1.5), Error);
}

}  // namespace
}  // namespace finverse::fsi
