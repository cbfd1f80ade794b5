// SO(3) utilities: exp/log round trip, and Ts^-1 as the inverse of the derivative of exp.
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "fem/rotation.hpp"

using namespace finverse::fem;

TEST(Rotation, ExpLogRoundTripIncludingSmallAndNearPi) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (double scale : {1e-14, 1e-6, 0.3, 2.0, 3.1}) {
    for (int k = 0; k < 20; ++k) {
      Vec3 axis(U(rng), U(rng), U(rng));
      axis.normalize();
      const Vec3 theta = scale * axis;
      const Mat3 R = exp_so3(theta);
      EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-14);
      EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
      EXPECT_LT((log_so3(R) - theta).norm(), 1e-12 * std::max(1.0, scale)) << "scale " << scale;
    }
  }
}

TEST(Rotation, TangentInverseMatchesDerivativeOfExp) {
  // dR R^T = skew(Ts dtheta): check Ts^-1 (spin of a finite-difference perturbation) = dtheta.
  const Vec3 theta(0.7, -0.4, 1.1);
  const Mat3 R = exp_so3(theta);
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    Vec3 d = Vec3::Zero();
    d(j) = h;
    const Mat3 dR = (exp_so3(theta + d) - exp_so3(theta - d)) / (2 * h);
    const Vec3 spin = unskew(dR * R.transpose());
    EXPECT_LT((tangent_inverse(theta) * spin - Vec3::Unit(j)).norm(), 1e-8);
  }
}
