// IQN-ILS (iqn_ils.hpp): the update against an independent least-squares solve of the same
// columns, finite termination on a linear map, the QR1 filter, reuse and the column limit.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include <Eigen/Dense>

#include "core/error.hpp"
#include "fsi/iqn_ils.hpp"
#include "linear_step.hpp"

namespace finverse::fsi {
namespace {

TEST(IqnIls, UpdateEqualsIndependentLeastSquares) {
  const int n = 20;
  const Eigen::MatrixXd a = test::symmetric_with_spectrum(n, -2.0, 0.5, 7);
  const Eigen::VectorXd b = test::random_vector(n, 8);
  IqnIlsOptions options;
  options.filter_epsilon = 0.0;
  IqnIls iqn({n, 0}, options);
  iqn.reset_time_step();
  std::vector<Eigen::VectorXd> ins, outs;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < 5; ++k) {
    ins.push_back(x);
    outs.push_back(a * x + b);
    x = iqn.accelerate(ins.back(), outs.back());
  }
  EXPECT_DOUBLE_EQ(iqn.last_omega(), 1.0);
  ASSERT_EQ(iqn.columns(), 4);
  // V = [r_k - r_{k-1}], W = [out_k - out_{k-1}] of the four pairs; alpha = argmin |V alpha + r_4|.
  Eigen::MatrixXd v(n, 4), w(n, 4);
  for (int k = 1; k < 5; ++k) {
    v.col(k - 1) = (outs[k] - ins[k]) - (outs[k - 1] - ins[k - 1]);
    w.col(k - 1) = outs[k] - outs[k - 1];
  }
  const Eigen::VectorXd r4 = outs[4] - ins[4];
  const Eigen::VectorXd alpha = v.colPivHouseholderQr().solve(-r4);
  const Eigen::VectorXd expected = outs[4] + w * alpha;
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
}

TEST(IqnIls, TerminatesOnLinearMapWithinSizePlusOne) {
  // A non-symmetric map with spectral radius 2.4: plain iteration diverges.
  const int n = 30;
  Eigen::MatrixXd a = test::symmetric_with_spectrum(n, -2.4, 0.6, 11);
  a += 0.3 * test::symmetric_with_spectrum(n, -1.0, 1.0, 12).triangularView<Eigen::StrictlyUpper>()
                 .toDenseMatrix();
  const Eigen::VectorXd b = test::random_vector(n, 13);
  const Eigen::VectorXd fixed =
      (Eigen::MatrixXd::Identity(n, n) - a).partialPivLu().solve(b);
  for (double eps : {0.0, 1e-2}) {
    IqnIlsOptions options;
    options.filter_epsilon = eps;
    IqnIls iqn({n, 0}, options);
    iqn.reset_time_step();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    int iterations = 0;
    for (; iterations < 2 * n; ++iterations) {
      const Eigen::VectorXd out = a * x + b;
      if ((out - x).norm() <= 1e-10 * out.norm()) break;
      x = iqn.accelerate(x, out);
    }
    std::printf("[ IQN-ILS ] n = %d, filter eps %.0e: %d iterations to 1e-10 (%d columns filtered)\n",
                n, eps, iterations + 1, iqn.filtered_columns());
    EXPECT_LE(iterations + 1, n + 1);
    EXPECT_LT((x - fixed).norm(), 1e-8 * fixed.norm());
  }
}

TEST(IqnIls, FilterDropsDependentColumns) {
  IqnIls iqn({5, 0});  // eps = 1e-2
  iqn.reset_time_step();
  const Eigen::VectorXd d = test::random_vector(5, 3);
  const Eigen::VectorXd r0 = test::random_vector(5, 4);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(5);
  // Residuals r0, r0 + d, r0 + 2d (+ 1e-6 noise): the second difference repeats the first.
  Eigen::VectorXd noise = Eigen::VectorXd::Zero(5);
  noise(0) = 1e-6;
  (void)iqn.accelerate(x0, x0 + r0);
  (void)iqn.accelerate(x0, x0 + r0 + d);
  EXPECT_EQ(iqn.columns(), 1);
  const Eigen::VectorXd next = iqn.accelerate(x0, x0 + r0 + 2.0 * d + noise);
  EXPECT_TRUE(next.allFinite());
  EXPECT_EQ(iqn.filtered_columns(), 1);
  EXPECT_EQ(iqn.columns(), 1);
}

TEST(IqnIls, ReuseKeepsColumnsOfLastQStepsAndLimitsColumns) {
  const int n = 10;
  const Eigen::MatrixXd a = test::symmetric_with_spectrum(n, -2.0, 0.5, 5);
  const Eigen::VectorXd b = test::random_vector(n, 6);
  auto run_step = [&](IqnIls& iqn, int iterations) {
    iqn.reset_time_step();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < iterations; ++k) x = iqn.accelerate(x, a * x + b);
    iqn.end_time_step(x, a * x + b);  // adds the last difference: `iterations` columns per step
  };
  IqnIlsOptions none;
  none.reused_time_steps = 0;
  none.filter_epsilon = 0.0;
  IqnIls no_reuse({n, 0}, none);
  run_step(no_reuse, 3);
  EXPECT_EQ(no_reuse.columns(), 0);

  IqnIlsOptions one = none;
  one.reused_time_steps = 1;
  IqnIls reuse({n, 0}, one);
  run_step(reuse, 3);
  EXPECT_EQ(reuse.columns(), 3);
  reuse.reset_time_step();
  // First iteration of the next step: the reused columns give a quasi-Newton update at once.
  (void)reuse.accelerate(Eigen::VectorXd::Zero(n), b);
  EXPECT_DOUBLE_EQ(reuse.last_omega(), 1.0);

  IqnIlsOptions limited = none;
  limited.reused_time_steps = 10;
  limited.max_columns = 4;
  IqnIls capped({n, 0}, limited);
  run_step(capped, 3);
  run_step(capped, 3);
  EXPECT_EQ(capped.columns(), 4);

  IqnIlsOptions bad;
  bad.filter_epsilon = 1.0;
  EXPECT_THROW(IqnIls({n, 0}, bad), Error);
  bad = IqnIlsOptions{};
  bad.initial_omega = 0.0;
  EXPECT_THROW(IqnIls({n, 0}, bad), Error);
}

}  // namespace
}  // namespace finverse::fsi

namespace finverse::fsi {
namespace {

// The size the brief names: 10^4 interface unknowns, up to 100 columns. A diagonal A suffices
// (IQN-ILS is invariant under an orthogonal change of basis); spectrum in [-3, 0.5].
class DiagonalStep : public CoupledStep {
 public:
  DiagonalStep(Eigen::VectorXd a, Eigen::VectorXd b) : a_(std::move(a)), b_(std::move(b)) {}
  void save() override {}
  void restore() override {}
  Eigen::VectorXd evaluate(const Eigen::VectorXd& x) override { return a_.cwiseProduct(x) + b_; }
  Eigen::VectorXd a_, b_;
};

TEST(IqnIls, TenThousandUnknownsWithHundredColumns) {
#ifdef NDEBUG
  const int n = 10000, steps = 6;
#else  // unoptimized (sanitized) builds: 34 s at full size, so a fifth of it, and no timing check
  const int n = 2000, steps = 6;
#endif
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(n, -3.0, 0.5);
  const Eigen::VectorXd b0 = test::random_vector(n, 21), b1 = test::random_vector(n, 22);
  DiagonalStep step(a, b0);
  CouplingOptions options;
  options.convergence.relative_tolerance = 1e-8;
  options.predictor = Predictor::Constant;
  options.max_iterations = 100;
  IqnIlsOptions iqn_options;  // defaults: q = 8, 100 columns
  ImplicitCoupling coupling({n, 0}, Eigen::VectorXd::Zero(n),
                            std::make_unique<IqnIls>(InterfaceLayout{n, 0}, iqn_options), options);
  int total = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 1; s <= steps; ++s) {
    step.b_ = b0 + std::sin(0.05 * s) * b1;
    total += coupling.advance(step, 0.1).iterations;
    const Eigen::VectorXd exact = step.b_.cwiseQuotient((1.0 - a.array()).matrix());
    EXPECT_LT((coupling.state() - exact).norm(), 1e-6 * exact.norm());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& iqn = dynamic_cast<const IqnIls&>(coupling.acceleration());
  std::printf("[ IQN-ILS ] n = %d, %d steps: %d iterations (mean %.1f), %d columns held, "
              "%.1f ms per iteration\n",
              n, steps, total, static_cast<double>(total) / steps, iqn.columns(),
              1e3 * seconds / total);
  EXPECT_LE(iqn.columns(), 100);
#ifdef NDEBUG
  EXPECT_LT(seconds / total, 0.5);  // measured 14 ms on the shared 2-core machine
#endif
}

}  // namespace
}  // namespace finverse::fsi
