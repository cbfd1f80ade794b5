// Regularized delta kernels (see delta_kernel.hpp). The smoothed kernels are the box average of
// the unsmoothed one, from the closed-form antiderivative of each piece (the square roots
// integrate to arcsines): a quadrature converges slowly there, because the square roots' branch
// points lie just outside the pieces.
#include "cfd/immersed/delta_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace finverse::cfd {
namespace {

double roma3(double r) {
  r = std::abs(r);
  if (r <= 0.5) return (1 + std::sqrt(1 - 3 * r * r)) / 3;
  if (r <= 1.5) return (5 - 3 * r - std::sqrt(1 - 3 * (1 - r) * (1 - r))) / 6;
  return 0;
}

double peskin4(double r) {
  r = std::abs(r);
  if (r <= 1) return (3 - 2 * r + std::sqrt(1 + 4 * r - 4 * r * r)) / 8;
  if (r <= 2) return (5 - 2 * r - std::sqrt(-7 + 12 * r - 4 * r * r)) / 8;
  return 0;
}

// Antiderivative of sqrt(1 - u^2).
double G(double u) {
  u = std::clamp(u, -1.0, 1.0);
  return 0.5 * (u * std::sqrt(1 - u * u) + std::asin(u));
}

// Phi(s) = int_0^s phi, for s >= 0 (phi is even, so Phi is odd); closed forms of each piece.
double roma3_integral(double s) {
  const double r3 = std::sqrt(3.0);
  const auto inner = [&](double x) { return (x + G(r3 * x) / r3) / 3; };
  const auto outer = [&](double x) { return (5 * x - 1.5 * x * x) / 6 + G(r3 * (1 - x)) / (6 * r3); };
  if (s <= 0.5) return inner(s);
  return inner(0.5) + outer(std::min(s, 1.5)) - outer(0.5);
}

double peskin4_integral(double s) {
  const double r2 = std::sqrt(2.0);
  const auto inner = [&](double x) { return (3 * x - x * x + G((2 * x - 1) / r2)) / 8; };
  const auto outer = [&](double x) { return (5 * x - x * x - G((2 * x - 3) / r2)) / 8; };
  if (s <= 1) return inner(s) - inner(0);
  return inner(1) - inner(0) + outer(std::min(s, 2.0)) - outer(1);
}

// The box average over [r - 1/2, r + 1/2]: Phi(r + 1/2) - Phi(r - 1/2).
template <class Integral>
double smoothed(Integral I, double r) {
  const auto Phi = [&](double s) { return s >= 0 ? I(s) : -I(-s); };
  return Phi(r + 0.5) - Phi(r - 0.5);
}

}  // namespace

DeltaKernel delta_kernel_from_name(const std::string& name) {
  if (name == "roma3") return DeltaKernel::Roma3;
  if (name == "peskin4") return DeltaKernel::Peskin4;
  if (name == "smooth3") return DeltaKernel::Smooth3;
  if (name == "smooth4") return DeltaKernel::Smooth4;
  throw Error("delta kernel: '" + name + "', expected roma3, peskin4, smooth3 or smooth4");
}

const char* delta_kernel_name(DeltaKernel k) {
  switch (k) {
    case DeltaKernel::Roma3:
      return "roma3";
    case DeltaKernel::Peskin4:
      return "peskin4";
    case DeltaKernel::Smooth3:
      return "smooth3";
    default:
      return "smooth4";
  }
}

double delta_kernel_half_support(DeltaKernel k) {
  switch (k) {
    case DeltaKernel::Roma3:
      return 1.5;
    case DeltaKernel::Peskin4:
      return 2.0;
    case DeltaKernel::Smooth3:
      return 2.0;
    default:
      return 2.5;
  }
}

double delta_kernel(DeltaKernel k, double r) {
  if (std::abs(r) >= delta_kernel_half_support(k)) return 0;
  switch (k) {
    case DeltaKernel::Roma3:
      return roma3(r);
    case DeltaKernel::Peskin4:
      return peskin4(r);
    case DeltaKernel::Smooth3:
      return std::max(0.0, smoothed(roma3_integral, r));
    default:
      return std::max(0.0, smoothed(peskin4_integral, r));
  }
}

}  // namespace finverse::cfd
