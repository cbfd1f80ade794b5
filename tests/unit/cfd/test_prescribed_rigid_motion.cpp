// A prescribed rigid motion (cfd/immersed/prescribed_rigid_motion.hpp): its velocity and
// acceleration are the time derivatives of its placement (checked by central differences), for
// harmonics, a constant rate and two rotations about axes that do not commute; a pose table
// reproduces the motion it samples; the plane motion's angle is continuous over whole turns.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/immersed/prescribed_rigid_motion.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

MotionChannel harmonic(double offset, double rate, double a, double f, double phase) {
  MotionChannel c;
  c.offset = offset;
  c.rate = rate;
  c.harmonics.push_back({a, f, phase});
  return c;
}

// Largest |v - dx/dt| and |a - dv/dt| over body points and times, by central differences.
std::array<double, 2> derivative_errors(const PrescribedRigidMotion& m, const std::vector<Vec3>& points) {
  const double d = 1e-5;
  double ev = 0, ea = 0;
  for (double t : {0.0, 0.13, 0.71, 1.9})
    for (const Vec3& X : points) {
      const PointKinematics k = m.point(m.pose(t), X);
      const PointKinematics lo = m.point(m.pose(t - d), X), hi = m.point(m.pose(t + d), X);
      for (int c = 0; c < 3; ++c) {
        ev = std::max(ev, std::abs(k.velocity[c] - (hi.position[c] - lo.position[c]) / (2 * d)));
        ea = std::max(ea, std::abs(k.acceleration[c] - (hi.velocity[c] - lo.velocity[c]) / (2 * d)));
      }
    }
  return {ev, ea};
}

TEST(PrescribedRigidMotion, VelocityAndAccelerationAreTheDerivativesOfThePlacement) {
  // Heave, surge at a constant rate, pitch about z and a flapping stroke about x afterwards.
  std::array<MotionChannel, 3> tr{harmonic(0.1, -0.4, 0.05, 1.3, 0.2), harmonic(0, 0, 0.3, 0.8, 0), MotionChannel{}};
  std::vector<PrescribedRigidMotion::Rotation> rot{{{0, 0, 2}, harmonic(0.1, 0, 0.6, 0.8, 1.0)},
                                                   {{1, 0, 0}, harmonic(0, 0.2, 0.4, 1.1, -0.5)}};
  const PrescribedRigidMotion m({0.25, 0, 0}, tr, rot);
  EXPECT_TRUE(m.moves());
  const auto e = derivative_errors(m, {{0, 0, 0}, {1, 0, 0.5}, {0.3, -0.2, 1.0}});
  EXPECT_LT(e[0], 1e-7);
  EXPECT_LT(e[1], 1e-6);
  // The pivot follows the translation alone, and the rotation keeps distances.
  const RigidPose p = m.pose(0.37);
  const PointKinematics piv = m.point(p, {0.25, 0, 0});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(piv.position[c], (c == 0 ? 0.25 : 0.0) + p.displacement[c], 1e-14);
  const PointKinematics a = m.point(p, {1, 0, 0.5}), b = m.point(p, {0.3, -0.2, 1.0});
  EXPECT_NEAR(norm(sub(a.position, b.position)), norm(sub(Vec3{1, 0, 0.5}, Vec3{0.3, -0.2, 1.0})), 1e-14);
}

TEST(PrescribedRigidMotion, APoseTableReproducesTheMotionItSamples) {
  // Samples of y = 0.2 sin(2 pi t), angle = 0.3 sin(2 pi t + 1), periodic in T = 1, 64 frames.
  const int n = 64;
  std::vector<double> t, v;
  for (int k = 0; k < n; ++k) {
    t.push_back(static_cast<double>(k) / n);
    v.push_back(0.2 * std::sin(2 * std::numbers::pi * t.back()));
    v.push_back(0.3 * std::sin(2 * std::numbers::pi * t.back() + 1));
  }
  std::array<MotionChannel, 3> tr{};
  tr[1].column = 0;
  MotionChannel angle;
  angle.column = 1;
  const PrescribedRigidMotion table({0, 0, 0}, tr, {{{0, 0, 1}, angle}}, TimeSpline(t, v, 2, 1.0));
  const PrescribedRigidMotion exact({0, 0, 0}, {MotionChannel{}, harmonic(0, 0, 0.2, 1, 0), MotionChannel{}},
                                    {{{0, 0, 1}, harmonic(0, 0, 0.3, 1, 1)}});
  for (double time : {0.05, 0.5, 1.37}) {
    const PointKinematics a = table.point(table.pose(time), {1, 0, 0});
    const PointKinematics b = exact.point(exact.pose(time), {1, 0, 0});
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a.position[c], b.position[c], 1e-5);
      EXPECT_NEAR(a.velocity[c], b.velocity[c], 1e-3);
    }
  }
  EXPECT_FALSE(table.span().has_value());  // periodic: any time
}

TEST(PrescribedRigidMotion, ThePlaneAngleIsContinuousOverWholeTurns) {
  MotionChannel spin;
  spin.rate = 2 * std::numbers::pi;  // one turn per second
  const PrescribedRigidMotion m({1, 2, 0}, {}, {{{0, 0, 1}, spin}});
  const RigidState s = m.plane_state(2.25);
  EXPECT_NEAR(s.angle, 4.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(s.angular_velocity, 2 * std::numbers::pi, 1e-12);
  const PrescribedRigidMotion tilted({0, 0, 0}, {}, {{{1, 0, 0}, spin}});
  EXPECT_THROW(tilted.plane_state(0), Error);
}

TEST(PrescribedRigidMotion, BadAxesValuesAndColumnsAreRefused) {
  EXPECT_THROW(PrescribedRigidMotion({0, 0, 0}, {}, {{{0, 0, 0}, MotionChannel{}}}), Error);
  EXPECT_THROW(PrescribedRigidMotion({0, 0, 0}, {harmonic(0, 0, NAN, 1, 0), MotionChannel{}, MotionChannel{}}, {}),
               Error);
  std::array<MotionChannel, 3> tr{};
  tr[0].column = 3;
  EXPECT_THROW(PrescribedRigidMotion({0, 0, 0}, tr, {}, TimeSpline({0, 1}, {0, 1}, 1, std::nullopt)), Error);
}

}  // namespace
}  // namespace finverse::cfd
