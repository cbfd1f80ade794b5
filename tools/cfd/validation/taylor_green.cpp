// The Taylor-Green validation case; see taylor_green.hpp.
#include "cfd/validation/taylor_green.hpp"

#include <cmath>
#include <ctime>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
constexpr double two_pi = 2 * std::numbers::pi;

double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }
}  // namespace

StretchedGrid taylor_green_grid(int n, double stretch) {
  if (n < 4 || !(stretch >= 0 && stretch < 1)) throw Error("taylor-green: need n >= 4 and 0 <= stretch < 1");
  std::vector<double> f(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double xi = two_pi * i / n;
    f[static_cast<std::size_t>(i)] = xi + stretch * std::sin(xi);
  }
  return StretchedGrid(Axis(f), Axis(f));
}

TaylorGreenResult run_taylor_green(const TaylorGreenSetup& s) {
  const double cpu0 = process_cpu_seconds();
  const StretchedGrid g = taylor_green_grid(s.n, s.stretch);
  TaylorGreenResult r;
  r.setup = s;
  r.steps = static_cast<int>(std::lround(s.t_end / s.dt));
  FlowOptions opt;
  opt.nu = s.nu;
  opt.dt = s.t_end / r.steps;
  opt.poisson.rtol = 1e-12;
  opt.helmholtz_rtol = 1e-13;
  opt.coupling_time = s.coupling_time;
  FlowSolver solver;
  solver.setup(g, FlowBoundary::all_periodic(), opt);
  solver.initialise(
      [](double x, double y, double, double) {
        return std::array<double, 3>{-std::cos(x) * std::sin(y), std::sin(x) * std::cos(y), 0.0};
      },
      [](double x, double y, double) { return -0.25 * (std::cos(2 * x) + std::cos(2 * y)); });
  long poisson = 0, helmholtz = 0;
  for (int n = 0; n < r.steps; ++n) {
    const StepStats st = solver.step();
    poisson += st.poisson_iterations;
    helmholtz += st.helmholtz_iterations;
    for (int c = 0; c < 2; ++c) r.momentum_drift = std::max(r.momentum_drift, std::abs(solver.momentum(c)));
  }
  r.mean_poisson_iterations = static_cast<double>(poisson) / r.steps;
  r.mean_helmholtz_iterations = static_cast<double>(helmholtz) / r.steps;
  r.max_divergence = solver.max_divergence();

  const double F = std::exp(-2 * s.nu * solver.time());
  // The pressure belongs to the Crank-Nicolson half step.
  const double Fp = std::exp(-2 * s.nu * (solver.time() - 0.5 * opt.dt));
  const Field ph = solver.pressure();
  double e2 = 0, vol = 0, pm = 0, em = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const double V = g.volume(i, j, 0);
      pm += V * ph(i, j, 0);
      em += V * (-0.25 * (std::cos(2 * g.xc(i)) + std::cos(2 * g.yc(j))) * Fp * Fp);
      vol += V;
    }
  pm /= vol, em /= vol;
  double ep = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const double x = g.xc(i), y = g.yc(j), V = g.volume(i, j, 0);
      const double du = solver.u(0)(i, j, 0) - (-std::cos(x) * std::sin(y) * F);
      const double dv = solver.u(1)(i, j, 0) - std::sin(x) * std::cos(y) * F;
      const double dp = (ph(i, j, 0) - pm) - (-0.25 * (std::cos(2 * x) + std::cos(2 * y)) * Fp * Fp - em);
      e2 += V * (du * du + dv * dv);
      ep += V * dp * dp;
      r.u_linf = std::max({r.u_linf, std::abs(du), std::abs(dv)});
      r.u.push_back(solver.u(0)(i, j, 0));
      r.v.push_back(solver.u(1)(i, j, 0));
      r.volume.push_back(V);
    }
  r.u_l2 = std::sqrt(e2 / vol);
  r.p_l2 = std::sqrt(ep / vol);
  r.cpu_seconds = process_cpu_seconds() - cpu0;
  return r;
}

double velocity_difference(const TaylorGreenResult& a, const TaylorGreenResult& b) {
  if (a.u.size() != b.u.size()) throw Error("taylor-green: runs on different grids");
  double s = 0, vol = 0;
  for (std::size_t m = 0; m < a.u.size(); ++m) {
    const double du = a.u[m] - b.u[m], dv = a.v[m] - b.v[m];
    s += a.volume[m] * (du * du + dv * dv);
    vol += a.volume[m];
  }
  return std::sqrt(s / vol);
}

}  // namespace finverse::cfd
