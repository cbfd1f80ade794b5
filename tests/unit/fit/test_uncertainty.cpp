// Uncertainty at the optimum: the Gauss-Newton covariance of a linear model equals
// s^2 (J^T J)^-1; a parameter the residuals ignore, one at its bound, one whose interval spans
// decades, and the scale direction of a ratio-only model are all reported not identified.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "fit/correlated_residual.hpp"
#include "fit/levenberg_marquardt.hpp"
#include "fit/uncertainty.hpp"
#include "fit_test_util.hpp"

namespace fit = finverse::fit;

namespace {

using fit::test::param;

// A linear model r = A z - b with fixed pseudo-random A and b (m = 60 residuals, n = 3).
struct Linear {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  Linear(int m, int n, unsigned seed) : a(m, n), b(m) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < n; ++j) a(i, j) = normal(rng);
      b(i) = normal(rng);
    }
  }
};

}  // namespace

TEST(Uncertainty, LinearModelCovarianceIsAnalytic) {
  const Linear lin(60, 3, 5);
  const fit::ParameterSpace space({param("x", -10, 10, fit::Scale::linear), param("y", -10, 10, fit::Scale::linear),
                                   param("z", -10, 10, fit::Scale::linear)});
  const Eigen::VectorXd z = lin.a.colPivHouseholderQr().solve(lin.b);
  const Eigen::VectorXd r = lin.a * z - lin.b;
  const fit::Uncertainty u = fit::compute_uncertainty(space, z, r, lin.a);

  const double s2 = r.squaredNorm() / (60 - 3);
  const Eigen::MatrixXd cov = s2 * (lin.a.transpose() * lin.a).inverse();
  EXPECT_EQ(u.degrees_of_freedom, 57);
  EXPECT_NEAR(u.residual_variance, s2, 1e-14 * s2);
  const double t = 2.0024654593;  // Student t, 57 degrees of freedom, 97.5 %
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(u.standard_error(j), std::sqrt(cov(j, j)), 1e-12 * std::sqrt(cov(j, j)));
    EXPECT_NEAR(u.lower95(j), z(j) - t * std::sqrt(cov(j, j)), 1e-8);
    EXPECT_NEAR(u.upper95(j), z(j) + t * std::sqrt(cov(j, j)), 1e-8);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(u.correlation(j, k), cov(j, k) / std::sqrt(cov(j, j) * cov(k, k)), 1e-12);
    EXPECT_EQ(u.identified[j], 1) << u.verdict[j];
  }
  const Eigen::VectorXd sv = lin.a.jacobiSvd().singularValues();
  EXPECT_NEAR((u.singular_values - sv).norm(), 0, 1e-12 * sv(0));
}

TEST(Uncertainty, InsensitiveParameterIsNotIdentified) {
  Linear lin(40, 3, 6);
  lin.a.col(2).setZero();  // the residuals ignore z
  const fit::ParameterSpace space({param("x", -10, 10, fit::Scale::linear), param("y", -10, 10, fit::Scale::linear),
                                   param("z", -10, 10, fit::Scale::linear)});
  Eigen::VectorXd z = Eigen::VectorXd::Zero(3);
  z.head(2) = lin.a.leftCols(2).colPivHouseholderQr().solve(lin.b);
  const fit::Uncertainty u = fit::compute_uncertainty(space, z, lin.a * z - lin.b, lin.a);
  EXPECT_EQ(u.identified[0], 1);
  EXPECT_EQ(u.identified[1], 1);
  EXPECT_EQ(u.identified[2], 0);
  EXPECT_TRUE(std::isinf(u.standard_error(2)));
  EXPECT_NE(u.verdict[2].find("singular"), std::string::npos) << u.verdict[2];
  EXPECT_EQ(u.singular_values(2), 0);
}

TEST(Uncertainty, ScaleOfARatioOnlyModelIsNotIdentified) {
  // Residuals that depend on log10(E1) - log10(E2) only (the displacement-driven quasi-static
  // trap): the common scale is a null direction, so neither modulus is identified.
  const fit::ParameterSpace space({param("E1", 1e5, 1e8, fit::Scale::log10), param("E2", 1e5, 1e8, fit::Scale::log10)});
  Eigen::MatrixXd j(30, 2);
  for (int i = 0; i < 30; ++i) {
    j(i, 0) = 0.1 * (i + 1);
    j(i, 1) = -0.1 * (i + 1);
  }
  Eigen::VectorXd z(2);
  z << 6.5, 6.0;
  Eigen::VectorXd r = Eigen::VectorXd::Constant(30, 1e-3);
  const fit::Uncertainty u = fit::compute_uncertainty(space, z, r, j);
  EXPECT_EQ(u.identified[0], 0);
  EXPECT_EQ(u.identified[1], 0);
  EXPECT_EQ(u.lower95(0), 0);  // 10^-inf
  EXPECT_TRUE(std::isinf(u.upper95(0)));
}

TEST(Uncertainty, ParameterAtItsBoundIsFlagged) {
  const fit::ParameterSpace space({param("E", 1e5, 1e8, fit::Scale::log10), param("nu", 0.15, 0.49, fit::Scale::linear)});
  const Linear lin(20, 2, 7);
  Eigen::VectorXd z(2);
  z << 8.0 - 1e-4, 0.3;  // within 1e-3 of the 3-decade range
  const fit::Uncertainty u = fit::compute_uncertainty(space, z, 1e-6 * lin.b, lin.a);
  EXPECT_EQ(u.identified[0], 0);
  EXPECT_EQ(u.verdict[0], "at bound");
  EXPECT_EQ(u.identified[1], 1) << u.verdict[1];
}

TEST(Uncertainty, WideIntervalsAreNotIdentified) {
  const fit::ParameterSpace space({param("E", 1e5, 1e8, fit::Scale::log10), param("nu", 0.15, 0.49, fit::Scale::linear)});
  Linear lin(20, 2, 8);
  lin.a *= 0.05;  // weak sensitivity against unit-size residuals
  Eigen::VectorXd z(2);
  z << 6.5, 0.3;
  const fit::Uncertainty u = fit::compute_uncertainty(space, z, lin.b, lin.a);
  EXPECT_EQ(u.verdict[0], "interval spans more than a decade");
  EXPECT_GT(u.upper95(0) / u.lower95(0), 10);
  EXPECT_EQ(u.verdict[1], "interval wider than the bounds");
}

TEST(Uncertainty, NoDegreesOfFreedom) {
  const fit::ParameterSpace space({param("x", -1, 1, fit::Scale::linear), param("y", -1, 1, fit::Scale::linear)});
  const fit::Uncertainty u = fit::compute_uncertainty(space, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2),
                                                      Eigen::MatrixXd::Identity(2, 2));
  EXPECT_EQ(u.identified[0], 0);
  EXPECT_TRUE(std::isinf(u.standard_error(0)));
  EXPECT_EQ(u.verdict[0], "no residual degrees of freedom");
}

TEST(Uncertainty, FiniteDifferenceJacobianOfALinearModel) {
  const Linear lin(30, 2, 9);
  const fit::ParameterSpace space({param("x", -3, 3, fit::Scale::linear), param("y", -3, 3, fit::Scale::linear)});
  struct F : fit::ResidualFunction {
    const Linear* lin;
    Eigen::VectorXd w = Eigen::VectorXd::Ones(10);
    int parameter_count() const override { return 2; }
    int residual_count() const override { return 30; }
    Eigen::VectorXd residuals(const Eigen::VectorXd& p) const override { return lin->a * p - lin->b; }
    const Eigen::VectorXd& sqrt_weights() const override { return w; }
  } f;
  f.lin = &lin;
  Eigen::VectorXd z(2);
  z << 0.5, 3.0;  // y at its upper bound: the step goes inward
  long evaluations = 0;
  const Eigen::MatrixXd j =
      fit::finite_difference_jacobian(space, f, z, f.residuals(z), 1e-4, false, 2, &evaluations);
  EXPECT_EQ(evaluations, 2);
  EXPECT_NEAR((j - lin.a).norm(), 0, 1e-9);
}

// Issue 45, deliverable 6: a smooth residual over a grid of nodes (a model's misfit) is found
// systematic and widens the intervals; independent noise is found white and changes nothing.
TEST(Uncertainty, SystematicMisfitWidensTheIntervalsAndSaysSo) {
  const int side = 12, n = side * side;
  fit::ResidualLayout layout{2, Eigen::Matrix3Xd(3, n)};
  for (int i = 0; i < side; ++i)
    for (int k = 0; k < side; ++k) layout.points.col(i * side + k) = Eigen::Vector3d(i / 11.0, 0, k / 11.0);
  const Eigen::Index m = 3 * 2 * n;
  Eigen::MatrixXd J(m, 2);
  Eigen::VectorXd smooth(m), noise(m);
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const Eigen::Index r = 3 * (b * n + i) + c;
        const Eigen::Vector3d x = layout.points.col(i);
        J(r, 0) = x.x() * (c == 1);
        J(r, 1) = x.x() * x.x() * (c == 1) + 0.1 * g(rng);
        smooth(r) = 1e-3 * std::sin(3 * x.x() + 2 * x.z() + c);
        noise(r) = 1e-3 * g(rng);
      }
  const fit::ParameterSpace space({param("a", -10, 10, fit::Scale::linear), param("b", -10, 10, fit::Scale::linear)});
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(2);

  const auto white = fit::estimate_residual_correlation(noise, layout);
  EXPECT_FALSE(white.systematic);
  EXPECT_LT(std::abs(white.neighbour), 0.2);
  const auto u0 = fit::compute_uncertainty(space, z, noise, J);
  const auto u1 = fit::compute_uncertainty(space, z, noise, J, {}, &layout);
  EXPECT_EQ(u0.upper95, u1.upper95);
  EXPECT_EQ(u1.verdict[0], "identified");

  const auto field = fit::estimate_residual_correlation(smooth, layout);
  EXPECT_TRUE(field.systematic);
  EXPECT_GT(field.length, 2 * field.spacing);
  EXPECT_LT(field.effective_residuals, 0.2 * static_cast<double>(m));
  const auto plain = fit::compute_uncertainty(space, z, smooth, J);
  const auto honest = fit::compute_uncertainty(space, z, smooth, J, {}, &layout);
  EXPECT_TRUE(honest.systematic_misfit);
  for (int j = 0; j < 2; ++j) {
    EXPECT_GT(honest.upper95(j) - honest.lower95(j), 2 * (plain.upper95(j) - plain.lower95(j))) << j;
    EXPECT_EQ(honest.verdict[j].rfind("model misfit dominates: ", 0), 0u) << honest.verdict[j];
  }
}

// Issue 45, deliverable 6: a model's misfit that repeats its shape at every sample (here a random
// smooth field over the fin, scaled with the load level, as another code's difference is) biases
// the estimate coherently. Over many such misfits, the 95 % intervals must cover the truth at
// least 79 % of the time (0.81 measured; 0.77 without the scale correction: each fit estimates the misfit's covariance
// from its one residual); the white intervals, and a sandwich that takes the samples as independent, must not come
// close. The test fails if the channel covariance or the scale correction is dropped.
TEST(Uncertainty, IntervalsCoverTheTruthUnderAMisfitSharedBySamples) {
  const int side = 12, n = side * side, samples = 4;
  fit::ResidualLayout layout{samples, Eigen::Matrix3Xd(3, n)};
  for (int i = 0; i < side; ++i)
    for (int k = 0; k < side; ++k) layout.points.col(i * side + k) = Eigen::Vector3d(i / 11.0, 0, k / 11.0);
  const Eigen::Index m = 3 * samples * n;
  const auto row = [&](int b, int i, int c) { return 3 * (static_cast<Eigen::Index>(b) * n + i) + c; };
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, 2);
  for (int b = 0; b < samples; ++b)
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d x = layout.points.col(i);
      const double level = (b + 1.0) / samples;
      J(row(b, i, 1), 0) = level * x.x() * x.x();
      J(row(b, i, 1), 1) = level * x.x() * (0.5 + x.z());
      J(row(b, i, 0), 1) = 0.2 * level * x.x();
    }
  Eigen::MatrixXd kernel(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      kernel(i, j) =
          std::exp(-(layout.points.col(i) - layout.points.col(j)).squaredNorm() / 0.18) + (i == j ? 1e-6 : 0.0);
  const Eigen::MatrixXd chol = kernel.llt().matrixL();
  const Eigen::MatrixXd solve = (J.transpose() * J).ldlt().solve(J.transpose());
  const fit::ParameterSpace space({param("a", -10, 10, fit::Scale::linear), param("b", -10, 10, fit::Scale::linear)});
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  const int draws = 100;
  int covered = 0, covered_white = 0, covered_independent = 0;
  for (int d = 0; d < draws; ++d) {
    Eigen::VectorXd ey(n), ex(n), w(m);
    for (int i = 0; i < n; ++i) ey(i) = g(rng), ex(i) = g(rng);
    for (Eigen::Index i = 0; i < m; ++i) w(i) = g(rng);
    const Eigen::VectorXd fy = 1e-2 * (chol * ey), fx = 3e-3 * (chol * ex);
    Eigen::VectorXd misfit = 1e-4 * w;
    for (int b = 0; b < samples; ++b)
      for (int i = 0; i < n; ++i) {
        misfit(row(b, i, 1)) += (b + 1.0) / samples * fy(i);
        misfit(row(b, i, 0)) += (b + 1.0) / samples * fx(i);
      }
    const Eigen::VectorXd z = solve * misfit;  // the estimate; the truth is 0
    const Eigen::VectorXd r = misfit - J * z;
    const auto u = fit::compute_uncertainty(space, z, r, J, {}, &layout);
    const auto white = fit::compute_uncertainty(space, z, r, J);
    if (d < 5)
      std::printf("neff %g channels %g length %g\n", u.effective_residuals, u.effective_channels,
                  u.misfit_correlation_length);
    ASSERT_TRUE(u.systematic_misfit);
    fit::ResidualCorrelation independent = fit::estimate_residual_correlation(r, layout);
    independent.channels = Eigen::MatrixXd(independent.channels.diagonal().asDiagonal());
    const Eigen::MatrixXd pinv = (J.transpose() * J).inverse();
    const Eigen::VectorXd v = (pinv * fit::correlated_gram(J, layout, independent) * pinv).diagonal();
    for (int j = 0; j < 2; ++j) {
      covered += u.lower95(j) <= 0 && 0 <= u.upper95(j);
      covered_white += white.lower95(j) <= 0 && 0 <= white.upper95(j);
      covered_independent += std::abs(z(j)) <= 1.96 * std::sqrt(v(j));
    }
  }
  const double total = 2.0 * draws;
  EXPECT_GE(covered / total, 0.79);
  EXPECT_LT(covered_white / total, 0.5);
  EXPECT_LT(covered_independent / total, covered / total - 0.1);
  std::printf("coverage: channel model %.2f, samples independent %.2f, white %.2f\n", covered / total,
              covered_independent / total, covered_white / total);
}
