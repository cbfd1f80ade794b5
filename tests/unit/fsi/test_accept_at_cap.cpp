// CouplingOptions::accept_at_cap (implicit_coupling.hpp): an operator H(x) with a jump and no fixed
// point (what an immersed boundary does when a cell centre sits on the moving wall) stops with
// CouplingNotConverged by default; with accept_at_cap the step ends with the best iterate
// re-evaluated, converged = false, and the coupling goes on.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "fsi/constant_relaxation.hpp"
#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi {
namespace {

// H(x) = 0.8 for x < 0.5, 0.2 otherwise: every x maps across the jump.
class JumpStep final : public CoupledStep {
 public:
  void save() override {}
  void restore() override {}
  Eigen::VectorXd evaluate(const Eigen::VectorXd& x) override {
    ++evaluations;
    last_in = x(0);
    return Eigen::VectorXd::Constant(1, x(0) < 0.5 ? 0.8 : 0.2);
  }
  void accept(const Eigen::VectorXd& x_in, const Eigen::VectorXd&) override { accepted_in = x_in(0); }
  int evaluations = 0;
  double last_in = 0, accepted_in = -1;
};

CouplingOptions options(bool accept) {
  CouplingOptions o;
  o.max_iterations = 7;
  o.divergence_iterations = 0;
  o.accept_at_cap = accept;
  o.predictor = Predictor::Constant;
  return o;
}

TEST(AcceptAtCap, WithoutItTheCapThrows) {
  JumpStep step;
  ImplicitCoupling c({1, 0}, Eigen::VectorXd::Constant(1, 0.1), std::make_unique<ConstantRelaxation>(0.3), options(false));
  EXPECT_THROW(c.advance(step, 0.1), CouplingNotConverged);
  EXPECT_EQ(step.evaluations, 7);
  EXPECT_EQ(c.steps(), 0);
}

TEST(AcceptAtCap, TheBestIterateIsReevaluatedAndAccepted) {
  JumpStep step;
  ImplicitCoupling c({1, 0}, Eigen::VectorXd::Constant(1, 0.1), std::make_unique<ConstantRelaxation>(0.3), options(true));
  const StepStatistics st = c.advance(step, 0.1);
  EXPECT_FALSE(st.converged);
  EXPECT_EQ(st.iterations, 8);
  EXPECT_EQ(step.evaluations, 8);
  // The accepted input is the one with the smallest |H(x) - x| among the 7 iterates: the closest
  // to the jump at 0.5, and the state is H of it.
  const double best = step.accepted_in;
  EXPECT_EQ(step.last_in, best);
  EXPECT_NEAR(st.absolute_residual, std::abs((best < 0.5 ? 0.8 : 0.2) - best), 1e-15);
  // The same iterates by hand: x <- x + 0.3 (H(x) - x) from 0.1, seven of them.
  double x = 0.1, hand_best = 0, hand_residual = 1e300;
  for (int m = 0; m < 7; ++m) {
    const double r = (x < 0.5 ? 0.8 : 0.2) - x;
    if (std::abs(r) < hand_residual) {
      hand_residual = std::abs(r);
      hand_best = x;
    }
    x += 0.3 * r;
  }
  EXPECT_EQ(best, hand_best);
  EXPECT_NEAR(st.absolute_residual, hand_residual, 1e-15);
  EXPECT_EQ(c.state()(0), best < 0.5 ? 0.8 : 0.2);
  EXPECT_EQ(c.steps(), 1);
  EXPECT_NO_THROW(c.advance(step, 0.1));
  EXPECT_EQ(c.steps(), 2);
}

}  // namespace
}  // namespace finverse::fsi
