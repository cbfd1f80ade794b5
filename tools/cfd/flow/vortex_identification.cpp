// Velocity gradient, vorticity and lambda_2 at cell centres (vortex_identification.hpp;
// Jeong & Hussain 1995).
#include "cfd/flow/vortex_identification.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "cfd/grid/grid_loops.hpp"

namespace finverse::cfd {

namespace {

// d f / d x at centre n of an axis from the values at n-1, n, n+1; which neighbours may be used is
// given by has_lo / has_hi. Three-point formula for unequal spacing (exact for quadratics).
double derivative(const Axis& ax, int n, bool has_lo, bool has_hi, double f_lo, double f0, double f_hi) {
  if (has_lo && has_hi) {
    const double a = ax.centre(n) - ax.centre(n - 1), b = ax.centre(n + 1) - ax.centre(n);
    return (-b / (a * (a + b))) * f_lo + ((b - a) / (a * b)) * f0 + (a / (b * (a + b))) * f_hi;
  }
  if (has_hi) return (f_hi - f0) / (ax.centre(n + 1) - ax.centre(n));
  if (has_lo) return (f0 - f_lo) / (ax.centre(n) - ax.centre(n - 1));
  return 0.0;  // a fluid cell with no fluid neighbour along this axis: no information
}

}  // namespace

VelocityGradient velocity_gradient(const StretchedGrid& grid, const std::array<const Field*, 3>& u, int i, int j,
                                   int k, const FluidMask& fluid) {
  VelocityGradient g{};
  const std::array<int, 3> c{i, j, k};
  for (int d = 0; d < grid.dim(); ++d) {
    std::array<int, 3> lo = c, hi = c;
    --lo[static_cast<std::size_t>(d)];
    ++hi[static_cast<std::size_t>(d)];
    const int n = c[static_cast<std::size_t>(d)];
    const auto usable = [&](const std::array<int, 3>& q, int m) {
      return m >= 0 && m < grid.n(d) && (!fluid || fluid(q[0], q[1], q[2]));
    };
    const bool has_lo = usable(lo, n - 1), has_hi = usable(hi, n + 1);
    for (int a = 0; a < 3; ++a) {
      const Field* f = u[static_cast<std::size_t>(a)];
      if (!f) continue;
      const double f0 = (*f)(i, j, k);
      const double fl = has_lo ? (*f)(lo[0], lo[1], lo[2]) : 0.0;
      const double fh = has_hi ? (*f)(hi[0], hi[1], hi[2]) : 0.0;
      g[static_cast<std::size_t>(a)][static_cast<std::size_t>(d)] = derivative(grid.axis(d), n, has_lo, has_hi, fl, f0, fh);
    }
  }
  return g;
}

double lambda2(const VelocityGradient& g) {
  std::array<std::array<double, 3>, 3> s, w;
  Eigen::Matrix3d m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      s[a][b] = 0.5 * (g[a][b] + g[b][a]);
      w[a][b] = 0.5 * (g[a][b] - g[b][a]);
    }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double v = 0;
      for (int c = 0; c < 3; ++c) v += s[a][c] * s[c][b] + w[a][c] * w[c][b];
      m(a, b) = v;
    }
  // S^2 + W^2 is symmetric in exact arithmetic; symmetrise the rounding. The iterative solver,
  // not the closed form: repeated eigenvalues (a pure rotation has two) lose half the digits in
  // the trigonometric formula.
  m = 0.5 * (m + m.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m, Eigen::EigenvaluesOnly);
  return es.eigenvalues()(1);  // ascending
}

VortexFields vortex_fields(const StretchedGrid& grid, const std::array<const Field*, 3>& u, const FluidMask& fluid) {
  const std::size_t n = grid.cells();
  VortexFields out{std::vector<double>(3 * n, 0.0), std::vector<double>(n, 0.0)};
  for_each_cell(grid, [&](int i, int j, int k) {
    if (fluid && !fluid(i, j, k)) return;
    const std::size_t m = static_cast<std::size_t>(i) +
                          static_cast<std::size_t>(grid.nx()) *
                              (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid.ny()) * static_cast<std::size_t>(k));
    const VelocityGradient g = velocity_gradient(grid, u, i, j, k, fluid);
    out.vorticity[3 * m + 0] = g[2][1] - g[1][2];
    out.vorticity[3 * m + 1] = g[0][2] - g[2][0];
    out.vorticity[3 * m + 2] = g[1][0] - g[0][1];
    out.lambda2[m] = lambda2(g);
  });
  return out;
}

}  // namespace finverse::cfd
