// The start-up push of the Turek-Hron CFD3 driver (turek_hron_cfd.hpp, TurekHronSetup::kick_*):
// zero outside its time window and when switched off, a velocity impulse at the blob's centre of
// exactly kick_velocity, and localised one diameter behind the flag's tip (a Gaussian of radius D)
// so that the cylinder's boundary layer does not feel it.
#include <gtest/gtest.h>

#include <cmath>

#include "cfd/validation/turek_hron_cfd.hpp"

namespace finverse::cfd {
namespace {

TEST(TurekHronKick, GivesTheBlobCentreTheRequestedVelocityOnlyInsideItsWindow) {
  const TurekHronGeometry g;
  TurekHronSetup ts;
  ts.variant = 3;
  ts.kick_velocity = 2.0;
  ts.kick_start = 2.0;
  ts.kick_duration = 0.25;
  const double D = 2 * g.radius, xc = g.tip_x() + D, yc = g.yc;
  EXPECT_EQ(turek_hron_kick(ts, g, xc, yc, 1.99), 0.0);
  EXPECT_EQ(turek_hron_kick(ts, g, xc, yc, 2.0), 0.0);
  EXPECT_EQ(turek_hron_kick(ts, g, xc, yc, 2.25), 0.0);
  EXPECT_EQ(turek_hron_kick(ts, g, xc, yc, 3.0), 0.0);
  // Midpoint rule over the window: the impulse per unit mass is the requested velocity.
  const int n = 4000;
  double impulse = 0;
  for (int k = 0; k < n; ++k) impulse += turek_hron_kick(ts, g, xc, yc, 2.0 + 0.25 * (k + 0.5) / n) * 0.25 / n;
  EXPECT_NEAR(impulse, 2.0, 1e-9);
  // Gaussian in space: e^-1 one radius D away, negligible at the cylinder.
  const double peak = turek_hron_kick(ts, g, xc, yc, 2.125);
  EXPECT_NEAR(turek_hron_kick(ts, g, xc, yc + D, 2.125) / peak, std::exp(-1.0), 1e-12);
  EXPECT_NEAR(turek_hron_kick(ts, g, xc - D, yc, 2.125) / peak, std::exp(-1.0), 1e-12);
  EXPECT_LT(turek_hron_kick(ts, g, g.xc, yc, 2.125) / peak, 1e-10);
  ts.kick_velocity = 0;
  EXPECT_EQ(turek_hron_kick(ts, g, xc, yc, 2.125), 0.0);
}

}  // namespace
}  // namespace finverse::cfd
