// Score test and BIC on synthetic linear problems with a known answer (loop/score_test.hpp,
// loop/information_criterion.hpp).
#include <random>

#include <Eigen/QR>
#include <gtest/gtest.h>

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
