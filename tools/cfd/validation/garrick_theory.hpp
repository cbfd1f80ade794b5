// Linear theory of a 2-D flat plate heaving in a stream, the reference of heaving_plate_garrick
// (issue 30, item 3b). Theodorsen (1935, NACA Report 496):
//     C(k) = F + i G = H_1(k) / (H_1(k) + i H_0(k)),   H_n = J_n - i Y_n,   k = omega b / U.
// Garrick (1936, NACA Report 567, pitch terms zero): for h = h0 sin(omega t), on (1/2) rho U^2 c,
//     C_T = 4 pi k^2 (h0/c)^2 (F^2 + G^2)   (all leading-edge suction),
//     C_P = 4 pi k^2 (h0/c)^2 F,            efficiency (F^2 + G^2) / F.
// The derivation and its quasi-steady check: docs/studies/garrick_heaving_plate.md.
#pragma once

#include <complex>

namespace finverse::cfd {

// C(k) for k > 0 (std::cyl_bessel_j / std::cyl_neumann).
std::complex<double> theodorsen(double k);

// Garrick's mean thrust and power coefficients of pure heave, on (1/2) rho U^2 c and
// (1/2) rho U^3 c; k = omega b / U = pi f c / U, h0 the heave amplitude over the chord c.
double garrick_heave_thrust_coefficient(double k, double h0_over_c);
double garrick_heave_power_coefficient(double k, double h0_over_c);

}  // namespace finverse::cfd
