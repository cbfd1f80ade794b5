// Circular Couette flow between immersed circles; see ib_couette.hpp.
#include "cfd/validation/ib_couette.hpp"

#include <chrono>
#include <cmath>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

IbCouetteResult run_ib_couette(const IbCouetteSetup& cs) {
  const auto t0 = std::chrono::steady_clock::now();
  const double L = 0.6;
  const StretchedGrid g(Axis::uniform(-L, L, cs.n), Axis::uniform(-L, L, cs.n));
  FlowBoundary b;  // no-slip box walls; they lie in the solid outside r2
  FlowOptions opt;
  opt.nu = cs.nu;
  const double h = 2 * L / cs.n, wall_speed = cs.omega * cs.r1;
  opt.dt = 0.5 * h / wall_speed;  // CFL 0.5 on every grid: dt ~ h, as the spatial order needs
  opt.helmholtz_rtol = 1e-12;
  opt.poisson.rtol = 1e-11;
  FlowSolver solver;
  solver.setup(g, b, opt);
  const std::vector<SolidRegion> regions{{Polygon::circle(0, 0, cs.r1, cs.polygon_vertices), false},
                                         {Polygon::circle(0, 0, cs.r2, cs.polygon_vertices), true}};
  const double omega = cs.omega, r1 = cs.r1;
  // Tangential velocity of the inner wall; the outer wall (r > (r1 + r2)/2) is at rest.
  solver.immerse(regions, [omega, r1, r2 = cs.r2](double x, double y, double, double) -> std::array<double, 3> {
    if (std::hypot(x, y) > 0.5 * (r1 + r2)) return {0, 0, 0};
    return {-omega * y, omega * x, 0};
  });
  solver.initialise({});
  IbCouetteResult r;
  r.ghost_cells = static_cast<long>(solver.immersed()->ghosts().size());
  long poisson = 0, momentum = 0;
  while (solver.time() < cs.t_end - 1e-12) {
    const StepStats st = solver.step();
    poisson += st.poisson_iterations;
    momentum += st.helmholtz_iterations;
    ++r.steps;
  }
  const double den = cs.r2 * cs.r2 - cs.r1 * cs.r1;
  const double A = -cs.omega * cs.r1 * cs.r1 / den, B = cs.omega * cs.r1 * cs.r1 * cs.r2 * cs.r2 / den;
  double e2 = 0, vol = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      if (!solver.fluid(i, j, 0)) continue;
      const double x = g.xc(i), y = g.yc(j), rr = std::hypot(x, y);
      const double ut = A * rr + B / rr;
      const double du = solver.u(0)(i, j, 0) + ut * y / rr, dv = solver.u(1)(i, j, 0) - ut * x / rr;
      const double V = g.volume(i, j, 0);
      e2 += V * (du * du + dv * dv);
      vol += V;
      r.u_max = std::max(r.u_max, std::hypot(du, dv));
    }
  r.u_l2 = std::sqrt(e2 / vol);
  r.mean_poisson_iterations = static_cast<double>(poisson) / static_cast<double>(std::max(r.steps, 1L));
  r.mean_momentum_iterations = static_cast<double>(momentum) / static_cast<double>(std::max(r.steps, 1L));
  r.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace finverse::cfd
