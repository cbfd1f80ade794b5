// Shared helpers of the cfd unit tests: manufactured solutions for div(beta grad p) = f, grid
// families for refinement studies, and error norms.
#pragma once

#include <cmath>
#include <functional>
#include <random>

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/poisson/poisson_solver.hpp"

namespace finverse::cfd::test {

// A smooth, non-symmetric exact solution p = cos(a x + 0.4) sin(b y + 0.2) cos(c z - 0.3) (c = 0 in
// 2-D) with beta = 1 + s x y (s = 0: constant coefficient), and f = beta lap p + grad beta . grad p.
struct Manufactured {
  int dim = 2;
  double a = 1.3, b = 0.9, c = 1.1, s = 0.0;

  double p(double x, double y, double z) const {
    return std::cos(a * x + 0.4) * std::sin(b * y + 0.2) * (dim == 3 ? std::cos(c * z - 0.3) : 1.0);
  }
  double beta(double x, double y, double) const { return 1 + s * x * y; }
  // Gradient component d.
  double grad(int d, double x, double y, double z) const {
    const double cz = dim == 3 ? std::cos(c * z - 0.3) : 1.0;
    if (d == 0) return -a * std::sin(a * x + 0.4) * std::sin(b * y + 0.2) * cz;
    if (d == 1) return b * std::cos(a * x + 0.4) * std::cos(b * y + 0.2) * cz;
    if (dim == 2) return 0;
    return -c * std::cos(a * x + 0.4) * std::sin(b * y + 0.2) * std::sin(c * z - 0.3);
  }
  double f(double x, double y, double z) const {
    const double k2 = a * a + b * b + (dim == 3 ? c * c : 0.0);
    return -beta(x, y, z) * k2 * p(x, y, z) + s * y * grad(0, x, y, z) + s * x * grad(1, x, y, z);
  }
};

// Right-hand side field and boundary values of a manufactured problem.
inline Field source(const StretchedGrid& g, const std::function<double(double, double, double)>& f) {
  Field out(g);
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) out(i, j, k) = f(g.xc(i), g.yc(j), g.zc(k));
  return out;
}

inline BoundaryValues boundary_values(const StretchedGrid& g, const BoundaryConditions& bc, const Manufactured& m) {
  BoundaryValues v;
  for (int s = 0; s < 2 * g.dim(); ++s) {
    const Side side = static_cast<Side>(s);
    const int d = side_axis(side);
    const double sign = side_is_high(side) ? 1.0 : -1.0;
    if (bc[side] == BcType::Dirichlet)
      v.sample(g, side, [&](double x, double y, double z) { return m.p(x, y, z); });
    else if (bc[side] == BcType::Neumann)
      v.sample(g, side, [&](double x, double y, double z) { return sign * m.grad(d, x, y, z); });
  }
  return v;
}

struct Errors {
  double l2 = 0, linf = 0;
};

// Error of p against exact at cell centres; with remove_means, both are shifted to zero
// volume-weighted mean first (all-Neumann problems).
inline Errors error(const StretchedGrid& g, const Field& p, const std::function<double(double, double, double)>& exact,
                    bool remove_means) {
  double mp = 0, me = 0, vol = 0;
  if (remove_means)
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
          const double v = g.volume(i, j, k);
          mp += v * p(i, j, k);
          me += v * exact(g.xc(i), g.yc(j), g.zc(k));
          vol += v;
        }
  if (remove_means) mp /= vol, me /= vol;
  Errors e;
  vol = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const double d = (p(i, j, k) - mp) - (exact(g.xc(i), g.yc(j), g.zc(k)) - me);
        const double v = g.volume(i, j, k);
        e.l2 += v * d * d;
        vol += v;
        e.linf = std::max(e.linf, std::abs(d));
      }
  e.l2 = std::sqrt(e.l2 / vol);
  return e;
}

// Stretched axis of refinement level l: uniform core [-0.5, 1] with spacing h0 / 2^l, geometric
// stretching to [-2, 3] with ratio r0^(1/2^l), i.e. samples of one smooth grid mapping.
inline Axis stretched_axis(int l, double h0 = 0.25, double r0 = 1.44) {
  const double s = std::pow(2.0, l);
  return Axis::stretched(-2.0, 3.0, -0.5, 1.0, h0 / s, std::pow(r0, 1.0 / s));
}

inline Field random_field(const StretchedGrid& g, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Field out(g);
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) out(i, j, k) = u(gen);
  return out;
}

}  // namespace finverse::cfd::test
