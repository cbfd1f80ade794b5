// 3-D Taylor-Green cost benchmark of the flow solver; see flow_cost_bench.hpp.
#include "cfd/validation/flow_cost_bench.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "core/elapsed.hpp"

namespace finverse::cfd {

namespace {

using clock_type = std::chrono::steady_clock;

Axis periodic_axis(int n, double stretch) {
  std::vector<double> f(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double xi = 2 * std::numbers::pi * i / n;
    f[static_cast<std::size_t>(i)] = xi + stretch * std::sin(xi);
  }
  return Axis(std::move(f));
}

}  // namespace

FlowCostResult run_flow_cost_bench(int n, int warmup, int steps, double stretch) {
  if (n < 8 || n % 4 != 0) throw std::invalid_argument("flow cost bench: n must be a multiple of 4, >= 8");
  if (warmup < 0 || steps < 1) throw std::invalid_argument("flow cost bench: need warmup >= 0 and steps >= 1");
  if (!(stretch >= 0 && stretch < 1)) throw std::invalid_argument("flow cost bench: need 0 <= stretch < 1");
  FlowCostResult r;
  r.n = n;
  r.steps = steps;
  const Axis a = periodic_axis(n, stretch);
  const StretchedGrid g(a, a, a);
  FlowOptions opt;
  opt.nu = 1.0 / 1600;
  opt.dt = 0;  // CFL-controlled, as in production runs
  opt.cfl = 0.5;
  opt.dt_max = 0.1;
  auto t0 = clock_type::now();
  FlowSolver solver;
  solver.setup(g, FlowBoundary::all_periodic(), opt);
  solver.initialise(
      [](double x, double y, double z, double) {
        return std::array<double, 3>{std::sin(x) * std::cos(y) * std::cos(z), -std::cos(x) * std::sin(y) * std::cos(z),
                                     0.0};
      },
      [](double x, double y, double z) { return (std::cos(2 * x) + std::cos(2 * y)) * (std::cos(2 * z) + 2) / 16; });
  r.setup_s = seconds_since(t0);
  for (int s = 0; s < warmup; ++s) solver.step();
  long poisson = 0, helmholtz = 0;
  t0 = clock_type::now();
  for (int s = 0; s < steps; ++s) {
    const StepStats st = solver.step();
    poisson += st.poisson_iterations;
    helmholtz += st.helmholtz_iterations;
  }
  const double wall = seconds_since(t0);
  r.seconds_per_step = wall / steps;
  r.ns_per_cell_step = 1e9 * r.seconds_per_step / static_cast<double>(g.cells());
  r.mean_poisson_iterations = static_cast<double>(poisson) / steps;
  r.mean_helmholtz_iterations = static_cast<double>(helmholtz) / steps;
  r.max_divergence = solver.max_divergence();
  return r;
}

}  // namespace finverse::cfd
