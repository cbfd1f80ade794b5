// The interface layout's checks and the relative convergence measure |x_out - x_in| / |x_out|
// with its absolute floor (convergence_measure.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "fsi/convergence_measure.hpp"

namespace finverse::fsi {
namespace {

TEST(InterfaceLayout, StacksAndChecksBlocks) {
  const InterfaceLayout layout{3, 3};
  const Eigen::VectorXd z = layout.stack(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(4, 5, 6));
  ASSERT_EQ(z.size(), 6);
  EXPECT_EQ(layout.position(z)(2), 3.0);
  EXPECT_EQ(layout.velocity(z)(0), 4.0);
  EXPECT_THROW((void)layout.stack(Eigen::Vector2d(1, 2), Eigen::Vector3d(4, 5, 6)), Error);
  EXPECT_THROW(layout.check(Eigen::VectorXd::Zero(5), "test"), Error);
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(6);
  bad(4) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(layout.check(bad, "test"), Error);
  EXPECT_THROW((InterfaceLayout{0, 0}.validate()), Error);
  EXPECT_THROW((InterfaceLayout{3, 2}.validate()), Error);
  EXPECT_NO_THROW((InterfaceLayout{3, 0}.validate()));
}

TEST(ConvergenceMeasure, RelativeOnDisplacementWithAbsoluteFloor) {
  const InterfaceLayout layout{2, 2};
  ConvergenceMeasure measure(layout, {1e-3, 1e-12, true});
  // Displacement (3, 4) against (3, 4.004): |r| = 0.004, |x_out| = 5.0032 -> 8.0e-4 < 1e-3.
  Eigen::VectorXd in(4), out(4);
  in << 3, 4, 0, 0;
  out << 3, 4.004, 100, 100;  // the velocity block is not measured
  EXPECT_TRUE(measure.measure(in, out));
  EXPECT_NEAR(measure.absolute(), 0.004, 1e-15);
  EXPECT_NEAR(measure.relative(), 0.004 / std::hypot(3.0, 4.004), 1e-15);
  out(1) = 4.01;  // 2.0e-3 > 1e-3
  EXPECT_FALSE(measure.measure(in, out));
  ASSERT_EQ(measure.relative_history().size(), 2u);

  // Whole vector measured: the velocity difference now counts.
  ConvergenceMeasure all(layout, {1e-3, 1e-12, false});
  out(1) = 4.004;
  EXPECT_FALSE(all.measure(in, out));

  // A surface at rest: the relative measure is undefined, the absolute floor decides.
  ConvergenceMeasure floor(layout, {1e-3, 1e-10, true});
  EXPECT_TRUE(floor.measure(Eigen::VectorXd::Zero(4), Eigen::VectorXd::Zero(4)));
  Eigen::VectorXd tiny = Eigen::VectorXd::Zero(4);
  tiny(0) = 1e-11;
  EXPECT_TRUE(floor.measure(Eigen::VectorXd::Zero(4), tiny));
  tiny(0) = 1e-9;
  EXPECT_FALSE(floor.measure(Eigen::VectorXd::Zero(4), tiny));
  floor.reset();
  EXPECT_TRUE(floor.relative_history().empty());

  // A non-finite output is measured as not converged (the loop reports it as divergence).
  Eigen::VectorXd nan_out = out;
  nan_out(0) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(measure.measure(in, nan_out));
}

TEST(ConvergenceMeasure, RejectsBadTolerances) {
  EXPECT_THROW(ConvergenceMeasure({2, 0}, {0.0, 0.0, true}), Error);
  EXPECT_THROW(ConvergenceMeasure({2, 0}, {-1.0, 1e-12, true}), Error);
  ConvergenceMeasure m({2, 0}, {1e-5, 0.0, true});
  EXPECT_THROW(m.measure(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)), Error);
}

}  // namespace
}  // namespace finverse::fsi
