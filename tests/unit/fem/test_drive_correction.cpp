// Tests of the root drive's harmonic correction (fem/drive_correction.hpp): on a fin-like node set
// (root on the z axis, fin in the x-z plane) whose root nodes already carry a prescribed motion,
//   - the correction adds the Legendre family's pitch about the root line (eta -1 .. +1 from the
//     ventral to the dorsal root node) and the heave along the plane normal (+y), ramped like the
//     root motion, and keeps the earlier prescriptions under it;
//   - a zero correction leaves every prescription as it was;
//   - a root of one node (no line to place the rays on) and a non-finite coefficient are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fem/drive_correction.hpp"
#include "fem/errors.hpp"

namespace finverse::fem {
namespace {


// Root nodes 0..4 at z = -0.004 .. 0.004 (x = 0), a second column at x = 0.01 (the fin's plane is
// x-z). Root node i: heave 1 mm sin(t), pitch 0.1 t about z.
Model corrected_root_nodes() {
  Model m;
  for (int col = 0; col < 2; ++col)
    for (int i = 0; i < 5; ++i) m.add_node(Vec3(0.01 * col, 0, -0.004 + 0.002 * i));
  for (int i = 0; i < 5; ++i) {
    m.prescribe(i, 1, [](double t) { return 1e-3 * std::sin(t); });
    m.prescribe(i, 5, [](double t) { return 0.1 * t; });
    for (int d : {0, 2, 3, 4}) m.fix(i, d);
  }
  return m;
}

double prescribed_at(const Model& m, int node, int dof, double t) {
  for (const auto& p : m.prescribed())
    if (p.node == node && p.dof == dof) return p.at(t);
  return NAN;
}

TEST(DriveCorrection, AddsTheLegendrePitchAndTheHeaveOnTopOfTheRootMotion) {
  Model m = corrected_root_nodes();
  DriveCorrection c;
  c.frequency = 2;
  c.first_time = 1.0;
  c.ramp = 0.5;
  c.pitch_sin = {0.02, 0.01, -0.03};
  c.pitch_cos = {0.005, 0, 0.01};
  c.heave_sin = 2e-4;
  c.heave_cos = -1e-4;
  c.apply(m, {0, 1, 2, 3, 4});
  for (double t : {1.1, 1.37, 2.0}) {
    const double wt = 2 * std::numbers::pi * 2 * t;
    for (int i = 0; i < 5; ++i) {
      const double eta = -1 + 0.5 * i;  // z = -0.004 .. 0.004
      const double p2 = 0.5 * (3 * eta * eta - 1);
      const double a = 0.02 + 0.01 * eta - 0.03 * p2, b = 0.005 + 0.01 * p2;
      EXPECT_NEAR(prescribed_at(m, i, 5, t), 0.1 * t + a * std::sin(wt) + b * std::cos(wt), 1e-15) << i;
      EXPECT_NEAR(prescribed_at(m, i, 1, t), 1e-3 * std::sin(t) + 2e-4 * std::sin(wt) - 1e-4 * std::cos(wt), 1e-15);
      for (int d : {0, 2, 3, 4}) EXPECT_EQ(prescribed_at(m, i, d, t), 0.0);
    }
  }
  // The ramp: nothing before t0 - ramp, half at its middle, the correction whole from t0 on.
  EXPECT_EQ(c.ramp_factor(0.4), 0.0);
  EXPECT_NEAR(c.ramp_factor(0.75), 0.5, 1e-15);
  EXPECT_EQ(c.ramp_factor(1.0), 1.0);
  EXPECT_NEAR(prescribed_at(m, 4, 1, 0.4), 1e-3 * std::sin(0.4), 1e-18);
  // The nodes off the root are untouched.
  for (int n = 5; n < 10; ++n) EXPECT_TRUE(std::isnan(prescribed_at(m, n, 5, 1.5)));
}

TEST(DriveCorrection, ZeroCorrectionKeepsThePrescriptions) {
  Model m = corrected_root_nodes();
  DriveCorrection c;
  c.frequency = 3;
  c.pitch_sin = {0, 0};
  c.pitch_cos = {0, 0};
  EXPECT_TRUE(c.is_zero());
  c.apply(m, {0, 1, 2, 3, 4});
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(prescribed_at(m, i, 5, 0.7), 0.1 * 0.7);
    EXPECT_EQ(prescribed_at(m, i, 1, 0.7), 1e-3 * std::sin(0.7));
  }
}

TEST(DriveCorrection, RefusesARootWithoutALineAndBadValues) {
  Model m = corrected_root_nodes();
  DriveCorrection c;
  c.frequency = 3;
  c.pitch_sin = {0.1};
  c.pitch_cos = {0};
  EXPECT_THROW(c.apply(m, {2}), InvalidInput);
  c.pitch_cos = {NAN};
  EXPECT_THROW(c.apply(m, {0, 1, 2}), InvalidInput);
  c.pitch_cos = {0};
  c.frequency = 0;
  EXPECT_THROW(c.apply(m, {0, 1, 2}), InvalidInput);
}

TEST(DriveCorrection, LegendrePolynomials) {
  for (double x : {-1.0, -0.3, 0.0, 0.55, 1.0}) {
    EXPECT_EQ(legendre(0, x), 1.0);
    EXPECT_EQ(legendre(1, x), x);
    EXPECT_NEAR(legendre(2, x), 0.5 * (3 * x * x - 1), 1e-15);
    EXPECT_NEAR(legendre(3, x), 0.5 * (5 * x * x * x - 3 * x), 1e-15);
  }
}

}  // namespace
}  // namespace finverse::fem
