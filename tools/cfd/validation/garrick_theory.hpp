// Linear (thin-aerofoil, inviscid, planar-wake) theory of a 2-D flat plate heaving in a stream,
// the reference of the heaving_plate_garrick validation case (issue 30, item 3b):
//
// Theodorsen's function (Theodorsen 1935, NACA Report 496), with the Hankel functions
// of the second kind H_n = J_n - i Y_n,
//     C(k) = F(k) + i G(k) = H_1(k) / (H_1(k) + i H_0(k)),      k = omega b / U,
// b the half chord. C -> 1 as k -> 0 (quasi-steady) and 1/2 as k -> infinity.
//
// Garrick (1936, "Propulsion of a flapping and oscillating airfoil", NACA Report 567; his thrust
// with the pitch terms set to zero): a plate in pure heave h(t) = h0 sin(omega t) has the mean
// thrust per unit span (all of it leading-edge suction: a plate at zero incidence has a normal
// pressure force with no component along the stream)
//     T = pi rho b omega^2 h0^2 (F^2 + G^2),
// and needs the mean power P = pi rho b U omega^2 h0^2 F (the work against the circulatory lift
// L_c = 2 pi rho U b C(k) h'; the added-mass lift does no work over a period), so that
//     C_T = T / (rho U^2 b) = pi k^2 (h0/b)^2 (F^2 + G^2) = 4 pi k^2 (h0/c)^2 (F^2 + G^2),
//     C_P = P / (rho U^3 b) = 4 pi k^2 (h0/c)^2 F,        efficiency T U / P = (F^2 + G^2) / F,
// coefficients on (1/2) rho U^2 c, c = 2 b. In the quasi-steady limit (C = 1) the thrust is the
// steady leading-edge suction pi rho U^2 c alpha^2 of the heave-induced angle alpha = -h'/U,
// averaged: pi rho c (omega h0)^2 / 2 = pi rho b omega^2 h0^2.
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
