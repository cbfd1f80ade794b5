// Theodorsen's function and Garrick's heave thrust (garrick_theory.hpp), the linear theory the
// heaving_plate_garrick case is graded against: C(k) against the three-digit values of the
// standard tables (Theodorsen 1935, NACA Report 496; e.g. Bisplinghoff, Ashley & Halfman 1955),
// its quasi-steady (k -> 0) and high-frequency (k -> infinity) limits, and the thrust's
// quasi-steady limit, the mean leading-edge suction pi rho c U^2 <alpha^2> of the heave-induced
// angle alpha = -h'/U.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/validation/garrick_theory.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

TEST(GarrickTheory, TheodorsenMatchesTables) {
  struct Row {
    double k, f, g;
  };
  for (const Row& r : {Row{0.1, 0.832, -0.172}, Row{0.5, 0.598, -0.151}, Row{1.0, 0.539, -0.100}}) {
    const std::complex<double> c = theodorsen(r.k);
    EXPECT_NEAR(c.real(), r.f, 6e-4) << "k = " << r.k;  // the tables' rounding
    EXPECT_NEAR(c.imag(), r.g, 6e-4) << "k = " << r.k;
  }
}

TEST(GarrickTheory, TheodorsenLimits) {
  // Quasi-steady: C = 1 - (pi/2) k + O(k^2 log k) in F, G = O(k log k).
  const std::complex<double> slow = theodorsen(1e-5);
  EXPECT_NEAR(slow.real(), 1.0, 1e-4);
  EXPECT_NEAR(slow.imag(), 0.0, 2e-4);
  EXPECT_LT(slow.imag(), 0.0);
  // High frequency: C -> 1/2 with G = O(1/k).
  const std::complex<double> fast = theodorsen(1e3);
  EXPECT_NEAR(fast.real(), 0.5, 1e-5);
  EXPECT_NEAR(fast.imag(), 0.0, 2e-4);
  EXPECT_THROW(theodorsen(0.0), Error);
}

TEST(GarrickTheory, HeaveThrustAndPower) {
  constexpr double pi = std::numbers::pi;
  // The formula with the tabulated C(1) = 0.539 - 0.100 i, h0 = c/40: C_T = 4 pi k^2 (h0/c)^2 |C|^2,
  // C_P = 4 pi k^2 (h0/c)^2 F, within the table's rounding (0.0005 in F: 0.2 %).
  const double h = 0.025;
  EXPECT_NEAR(garrick_heave_thrust_coefficient(1.0, h) / (4 * pi * h * h * (0.539 * 0.539 + 0.100 * 0.100)), 1.0,
              2e-3);
  EXPECT_NEAR(garrick_heave_power_coefficient(1.0, h) / (4 * pi * h * h * 0.539), 1.0, 2e-3);
  // C_T ~ h0^2.
  EXPECT_NEAR(garrick_heave_thrust_coefficient(1.5, 2 * h) / garrick_heave_thrust_coefficient(1.5, h), 4.0, 1e-12);
  // Quasi-steady limit: alpha = omega h0 cos(omega t) / U, suction pi rho c U^2 <alpha^2>, on
  // (1/2) rho U^2 c: C_T = 2 pi (omega h0 / U)^2 / 2 = pi (2 k h0 / c)^2.
  const double k = 1e-5, alpha = 2 * k * h;
  EXPECT_NEAR(garrick_heave_thrust_coefficient(k, h) / (pi * alpha * alpha), 1.0, 1e-4);
  // Propulsive efficiency (F^2 + G^2) / F: 1 quasi-steadily, 1/2 at high frequency.
  EXPECT_NEAR(garrick_heave_thrust_coefficient(k, h) / garrick_heave_power_coefficient(k, h), 1.0, 1e-4);
  EXPECT_NEAR(garrick_heave_thrust_coefficient(1e3, h) / garrick_heave_power_coefficient(1e3, h), 0.5, 1e-4);
}

}  // namespace
}  // namespace finverse::cfd
