// Score test and BIC on synthetic linear problems with a known answer (loop/score_test.hpp,
// loop/information_criterion.hpp).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "fit/residual_layout.hpp"
#include "loop/errors.hpp"
#include "loop/information_criterion.hpp"
#include "loop/score_test.hpp"

namespace finverse::loop {
namespace {

Eigen::MatrixXd random_matrix(int m, int n, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd a(m, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) a(i, j) = g(rng);
  return a;
}

// y = X b + 0.5 z_planted + noise; the fit of y by X leaves r; among candidate columns the
// planted one scores first, a column inside span(X) scores 0, and unrelated ones stay near chi^2_1.
TEST(ScoreTest, PlantedColumnRanksFirstAndSpanColumnScoresZero) {
  std::mt19937 rng(7);
  const int m = 300, n = 4;
  const Eigen::MatrixXd x = random_matrix(m, n, rng);
  const Eigen::MatrixXd z = random_matrix(m, 4, rng);  // candidates; column 2 is planted
  std::normal_distribution<double> noise(0, 0.1);
  Eigen::VectorXd y = x * Eigen::Vector4d(1, -2, 0.5, 3) + 0.05 * z.col(2);
  for (int i = 0; i < m; ++i) y(i) += noise(rng);
  const Eigen::VectorXd b = x.colPivHouseholderQr().solve(y);
  const Eigen::VectorXd r = x * b - y;  // prediction - data
  const Eigen::MatrixXd q = orthonormal_basis(x);
  ASSERT_EQ(q.cols(), n);

  double best = -1;
  int best_col = -1;
  for (int c = 0; c < 4; ++c) {
    const auto s = score_test(r, q, n, z.col(c));
    if (s.statistic > best) best = s.statistic, best_col = c;
  }
  EXPECT_EQ(best_col, 2);
  const auto planted = score_test(r, q, n, z.col(2));
  EXPECT_GT(planted.statistic, 50.0);
  EXPECT_LT(planted.p_value, 1e-6);
  // The one-step estimate recovers the planted coefficient's size (sign: it removes r).
  EXPECT_NEAR(planted.step(0), 0.05, 0.02);

  // A combination of the fitted columns: in span(J), score 0 and projected fraction 0.
  const Eigen::VectorXd in_span = x * Eigen::Vector4d(0.3, 1, -2, 0.1);
  const auto zero = score_test(r, q, n, in_span);
  EXPECT_EQ(zero.statistic, 0.0);
  EXPECT_LT(zero.projected_fraction, 1e-8);
  EXPECT_EQ(zero.p_value, 1.0);
  // A planted column plus a span part scores as the planted column alone.
  const auto mixed = score_test(r, q, n, z.col(2) + in_span);
  EXPECT_NEAR(mixed.statistic, planted.statistic, 1e-6 * planted.statistic);
}

// Issue 45, deliverable 4. A smooth misfit over a 10 x 10 grid of nodes, repeated over 8 frames
// with the beat's phase (what the root drive leaves), against smooth candidates with their own
// phases. Under the white test most candidates are "significant"; the robust test, which
// estimates the residual's correlation, keeps the false alarms near the nominal rate and still
// ranks a planted candidate first and significant.
TEST(ScoreTest, RobustScoreKnowsTheResidualIsCorrelated) {
  const int side = 10, nodes = side * side, frames = 8, candidates = 6;
  fit::ResidualLayout layout{frames, Eigen::Matrix3Xd(3, nodes)};
  for (int i = 0; i < side; ++i)
    for (int k = 0; k < side; ++k) layout.points.col(i * side + k) = Eigen::Vector3d(i / 9.0, k / 9.0, 0);
  Eigen::MatrixXd kernel(nodes, nodes);
  for (int i = 0; i < nodes; ++i)
    for (int j = 0; j < nodes; ++j)
      kernel(i, j) =
          std::exp(-(layout.points.col(i) - layout.points.col(j)).squaredNorm() / 0.18) + (i == j ? 1e-6 : 0.0);
  const Eigen::MatrixXd chol = kernel.llt().matrixL();
  const int m = 3 * nodes * frames;
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  // A field over the nodes moving with phase phi at frame k, in the y component.
  const auto moving = [&](double phi, double amplitude) {
    Eigen::VectorXd e(nodes), out = Eigen::VectorXd::Zero(m);
    for (int i = 0; i < nodes; ++i) e(i) = g(rng);
    const Eigen::VectorXd f = amplitude * (chol * e);
    for (int k = 0; k < frames; ++k)
      for (int i = 0; i < nodes; ++i) out(3 * (k * nodes + i) + 1) = f(i) * std::cos(2 * M_PI * k / frames + phi);
    return out;
  };
  Eigen::MatrixXd x(m, 2);
  x.col(0) = moving(0, 1);
  x.col(1) = moving(1, 1);
  const Eigen::MatrixXd q = orthonormal_basis(x);
  std::vector<Eigen::VectorXd> s;
  for (int c = 0; c < candidates; ++c) s.push_back(moving(0.5 * c, 1));

  int alarms_white = 0, alarms_robust = 0, tests = 0;
  for (int draw = 0; draw < 20; ++draw) {
    Eigen::VectorXd misfit = moving(0.3, 1e-2) + moving(2.0, 5e-3);
    for (int i = 0; i < m; ++i) misfit(i) += 1e-4 * g(rng);
    const Eigen::VectorXd r = misfit - q * (q.transpose() * misfit);
    for (int c = 0; c < candidates; ++c, ++tests) {
      alarms_white += score_test(r, q, 2, s[c]).p_value < 0.05;
      const auto robust = score_test(r, q, 2, s[c], 1e-8, &layout);
      EXPECT_TRUE(robust.correlated);
      alarms_robust += robust.p_value < 0.05;
    }
  }
  std::printf("false alarms at 5 %%: white %d, robust %d of %d\n", alarms_white, alarms_robust, tests);
  EXPECT_GT(alarms_white, tests / 2);
  EXPECT_LE(alarms_robust, tests / 6);

  // The planted candidate 4, three times the misfit's size.
  Eigen::VectorXd data = moving(0.3, 1e-2) + 3e-2 * s[4];
  const Eigen::VectorXd r = data - q * (q.transpose() * data);
  double best = -1;
  int best_c = -1;
  for (int c = 0; c < candidates; ++c) {
    const auto robust = score_test(r, q, 2, s[c], 1e-8, &layout);
    if (robust.statistic > best) best = robust.statistic, best_c = c;
    if (c == 4) {
      EXPECT_LT(robust.p_value, 1e-3);
    }
  }
  EXPECT_EQ(best_c, 4);
}

TEST(ScoreTest, TwoColumnCandidateHasTwoDegreesOfFreedom) {
  std::mt19937 rng(3);
  const Eigen::MatrixXd x = random_matrix(120, 2, rng);
  const Eigen::MatrixXd s = random_matrix(120, 2, rng);
  const Eigen::VectorXd r = random_matrix(120, 1, rng).col(0);
  const auto res = score_test(r, orthonormal_basis(x), 2, s);
  EXPECT_EQ(res.degrees_of_freedom, 2);
  EXPECT_EQ(res.step.size(), 2);
  EXPECT_GT(res.p_value, 0.0);
  EXPECT_THROW(score_test(r.head(10), orthonormal_basis(x), 2, s), InvalidInput);
}

TEST(ScoreTest, ChiSquareTailMatchesKnownValues) {
  EXPECT_NEAR(chi2_tail(3.841458820694124, 1), 0.05, 1e-9);
  EXPECT_NEAR(chi2_tail(5.991464547107979, 2), 0.05, 1e-9);
  EXPECT_NEAR(chi2_tail(20.0, 3), 1.6974e-4, 1e-7);
  EXPECT_EQ(chi2_tail(0, 1), 1.0);
}

// Polynomial data of degree 2 with noise: BIC of least-squares fits of degree 0..5 is lowest at 2.
TEST(Bic, PicksTheTrueOrder) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, 0.05);
  const int m = 200;
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(m, -1, 1), y(m);
  for (int i = 0; i < m; ++i) y(i) = 0.3 - t(i) + 0.8 * t(i) * t(i) + noise(rng);
  int best_order = -1;
  double best = INFINITY;
  for (int order = 0; order <= 5; ++order) {
    Eigen::MatrixXd a(m, order + 1);
    for (int j = 0; j <= order; ++j) a.col(j) = t.array().pow(j);
    const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
    const double b = bic((a * c - y).squaredNorm(), m, order + 1);
    if (b < best) best = b, best_order = order;
  }
  EXPECT_EQ(best_order, 2);
  EXPECT_THROW(bic(-1, 10, 1), InvalidInput);
}

}  // namespace
}  // namespace finverse::loop
