// Theodorsen's function and Garrick's heave thrust; see garrick_theory.hpp.
#include "cfd/validation/garrick_theory.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::cfd {

std::complex<double> theodorsen(double k) {
  if (!(k > 0)) throw Error("theodorsen: the reduced frequency must be > 0");
  // H_n^(2)(k) = J_n(k) - i Y_n(k).
  const std::complex<double> h0(std::cyl_bessel_j(0.0, k), -std::cyl_neumann(0.0, k));
  const std::complex<double> h1(std::cyl_bessel_j(1.0, k), -std::cyl_neumann(1.0, k));
  return h1 / (h1 + std::complex<double>(0, 1) * h0);
}

double garrick_heave_thrust_coefficient(double k, double h0_over_c) {
  return 4 * std::numbers::pi * k * k * h0_over_c * h0_over_c * std::norm(theodorsen(k));
}

double garrick_heave_power_coefficient(double k, double h0_over_c) {
  return 4 * std::numbers::pi * k * k * h0_over_c * h0_over_c * theodorsen(k).real();
}

}  // namespace finverse::cfd
