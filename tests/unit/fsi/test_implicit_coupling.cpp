// The coupling loop (implicit_coupling.hpp): (d) divergence detection and the iteration cap give
// the named errors and leave the participants restored to the step's start; (e) restore() before
// every evaluate(), save() once per step; the predictors; the progress callback.
#include <gtest/gtest.h>

#include <limits>

#include "fsi/aitken.hpp"
#include "fsi/constant_relaxation.hpp"
#include "linear_step.hpp"

namespace finverse::fsi {
namespace {

CouplingOptions options_with(Predictor predictor, double tolerance = 1e-10) {
  CouplingOptions options;
  options.convergence.relative_tolerance = tolerance;
  options.predictor = predictor;
  return options;
}

TEST(ImplicitCoupling, GrowingResidualIsReportedAsDivergence) {
  // H(x) = -2 x + 1 with omega = 1: the residual doubles every iteration.
  test::LinearStep step(-2.0 * Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Ones(3));
  ImplicitCoupling coupling({3, 0}, Eigen::VectorXd::Zero(3), std::make_unique<ConstantRelaxation>(1.0),
                            options_with(Predictor::Constant), 0.0);
  try {
    (void)coupling.advance(step, 0.5);
    FAIL() << "expected CouplingDiverged";
  } catch (const CouplingDiverged& e) {
    const std::string message = e.what();
    std::printf("[ coupling ] %s\n", message.c_str());
    EXPECT_EQ(message.rfind("coupling diverged at step 1 (time 0.5): residual ", 0), 0u);
    EXPECT_NE(message.find("after 5 iterations"), std::string::npos);  // 4 growths in a row
    EXPECT_EQ(e.statistics.iterations, 5);
    ASSERT_EQ(e.statistics.residual_history.size(), 5u);
    EXPECT_FALSE(e.statistics.converged);
  }
  EXPECT_EQ(step.log.back(), "restore");  // the last good state is put back
  EXPECT_EQ(step.accepts, 0);
  EXPECT_EQ(coupling.steps(), 0);
  EXPECT_EQ(coupling.time(), 0.0);
}

TEST(ImplicitCoupling, IterationCapIsReportedAsNotConverged) {
  // H(x) = 0.9 x + 1: converges with omega = 1, but slowly; the cap of 10 stops it.
  test::LinearStep step(0.9 * Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Ones(2));
  CouplingOptions options = options_with(Predictor::Constant, 1e-12);
  options.max_iterations = 10;
  ImplicitCoupling coupling({2, 0}, Eigen::VectorXd::Zero(2), std::make_unique<ConstantRelaxation>(1.0),
                            options);
  try {
    (void)coupling.advance(step, 0.25);
    FAIL() << "expected CouplingNotConverged";
  } catch (const CouplingNotConverged& e) {
    const std::string message = e.what();
    std::printf("[ coupling ] %s\n", message.c_str());
    EXPECT_EQ(message.rfind("coupling did not converge at step 1 (time 0.25): residual ", 0), 0u);
    EXPECT_NE(message.find("after 10 iterations"), std::string::npos);
    EXPECT_EQ(e.statistics.iterations, 10);
    // 0.9^m decay of the residual: the history is independent evidence of the iterations run.
    EXPECT_NEAR(e.statistics.residual_history[9] / e.statistics.residual_history[8],
                0.9 * (1.0 - std::pow(0.9, 9)) / (1.0 - std::pow(0.9, 10)), 1e-12);
  }
  EXPECT_EQ(step.evaluations, 10);
  EXPECT_EQ(step.log.back(), "restore");

  // With divergence detection off, the growing residual runs into the cap instead.
  test::LinearStep growing(-2.0 * Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Ones(3));
  options.divergence_iterations = 0;
  options.max_iterations = 7;
  ImplicitCoupling uncapped({3, 0}, Eigen::VectorXd::Zero(3), std::make_unique<ConstantRelaxation>(1.0),
                            options);
  EXPECT_THROW((void)uncapped.advance(growing, 0.1), CouplingNotConverged);
}

TEST(ImplicitCoupling, NonFiniteOutputAndLaterStepsNameTheirStep) {
  test::LinearStep step(Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Ones(2));
  ImplicitCoupling coupling({2, 0}, Eigen::VectorXd::Zero(2), std::make_unique<ConstantRelaxation>(1.0),
                            options_with(Predictor::Constant), 1.0);
  const StepStatistics first = coupling.advance(step, 0.1);  // H constant: 2 iterations
  EXPECT_EQ(first.iterations, 2);
  EXPECT_TRUE(first.converged);
  step.set_b(Eigen::VectorXd::Constant(2, std::numeric_limits<double>::quiet_NaN()));
  try {
    (void)coupling.advance(step, 0.1);
    FAIL() << "expected CouplingDiverged";
  } catch (const CouplingDiverged& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("coupling diverged at step 2 (time 1.2): residual ", 0), 0u) << message;
    EXPECT_NE(message.find("not finite"), std::string::npos);
  }
}

TEST(ImplicitCoupling, RestoresBeforeEveryEvaluationAndSavesOncePerStep) {
  const Eigen::MatrixXd a = test::symmetric_with_spectrum(8, -2.0, 0.4, 3);
  test::LinearStep step(a, test::random_vector(8, 4));
  ImplicitCoupling coupling({8, 0}, Eigen::VectorXd::Zero(8),
                            std::make_unique<AitkenRelaxation>(InterfaceLayout{8, 0}),
                            options_with(Predictor::Constant, 1e-9));
  int total = 0;
  for (int n = 0; n < 3; ++n) total += coupling.advance(step, 0.1).iterations;
  EXPECT_EQ(step.saves, 3);
  EXPECT_EQ(step.accepts, 3);
  EXPECT_EQ(step.evaluations, total);
  EXPECT_EQ(step.restores, total);
  EXPECT_EQ(step.evaluations_without_restore, 0);
  // Order within a step: begin, save, then (restore, evaluate) pairs, then accept.
  ASSERT_GE(step.log.size(), 5u);
  EXPECT_EQ(step.log[0], "begin");
  EXPECT_EQ(step.log[1], "save");
  EXPECT_EQ(step.log[2], "restore");
  EXPECT_EQ(step.log[3], "evaluate");
  EXPECT_EQ(step.info().step, 3);
  EXPECT_NEAR(step.info().time, 0.2, 1e-15);
  EXPECT_NEAR(coupling.time(), 0.3, 1e-15);
  std::printf("[ coupling ] 3 steps, %d evaluations, %d restores, %d saves\n", step.evaluations,
              step.restores, step.saves);
}

TEST(ImplicitCoupling, PredictorsAndProgress) {
  // Constant velocity (the paper's step 1): X = X^{N-1} + dt V^{N-1}, V = V^{N-1}.
  const InterfaceLayout layout{2, 2};
  Eigen::VectorXd initial(4);
  initial << 1, 2, 3, 4;
  test::LinearStep step(Eigen::MatrixXd::Zero(4, 4), Eigen::Vector4d(5, 6, 7, 8));
  ImplicitCoupling coupling(layout, initial, std::make_unique<ConstantRelaxation>(1.0),
                            options_with(Predictor::ConstantVelocity));
  std::vector<IterationReport> reports;
  coupling.set_progress([&](const IterationReport& r) { reports.push_back(r); });
  const StepStatistics stats = coupling.advance(step, 0.5);
  EXPECT_EQ(step.inputs[0], Eigen::Vector4d(2.5, 4.0, 3.0, 4.0));
  ASSERT_EQ(reports.size(), static_cast<std::size_t>(stats.iterations));
  for (std::size_t i = 0; i < reports.size(); ++i) {
    EXPECT_EQ(reports[i].iteration, static_cast<int>(i) + 1);
    EXPECT_EQ(reports[i].residual, stats.residual_history[i]);
    EXPECT_EQ(reports[i].step, 1);
  }
  EXPECT_EQ(coupling.state(), Eigen::Vector4d(5, 6, 7, 8));
  EXPECT_EQ(progress_line({12, 0.06, 3, 1.234e-4, 1.0, 0.31}),
            "step 12 (time 0.06): iteration 3, residual 1.23e-04, omega 0.31");

  // Linear extrapolation: the third step starts from 2 x^2 - x^1.
  test::LinearStep lin(Eigen::MatrixXd::Zero(2, 2), Eigen::Vector2d(1, 1));
  ImplicitCoupling extrapolating({2, 0}, Eigen::Vector2d(0, 0),
                                 std::make_unique<ConstantRelaxation>(1.0),
                                 options_with(Predictor::Linear));
  (void)extrapolating.advance(lin, 0.1);
  lin.set_b(Eigen::Vector2d(3, 5));
  (void)extrapolating.advance(lin, 0.1);
  const std::size_t first_of_third = lin.inputs.size();
  (void)extrapolating.advance(lin, 0.1);
  EXPECT_EQ(lin.inputs[first_of_third], Eigen::Vector2d(5, 9));

  // Bad set-ups and participants.
  EXPECT_THROW(ImplicitCoupling({2, 0}, Eigen::Vector2d(0, 0),
                                std::make_unique<ConstantRelaxation>(1.0),
                                options_with(Predictor::ConstantVelocity)),
               Error);
  EXPECT_THROW(ImplicitCoupling({2, 0}, Eigen::Vector3d(0, 0, 0),
                                std::make_unique<ConstantRelaxation>(1.0),
                                options_with(Predictor::Constant)),
               Error);
  EXPECT_THROW((void)extrapolating.advance(lin, 0.0), Error);
  struct WrongSize : CoupledStep {
    void save() override {}
    void restore() override {}
    Eigen::VectorXd evaluate(const Eigen::VectorXd&) override { return Eigen::VectorXd::Zero(3); }
  } wrong;
  try {
    (void)extrapolating.advance(wrong, 0.1);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("returned an interface vector of size 3, expected 2"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace finverse::fsi
