// Step 4 of the time loop: the time step and the health check.
//
// dt is either fixed or chosen for a target convective CFL number dt max_P sum_d |u_d|/h_d (the
// Crank-Nicolson diffusion needs no viscous limit), growing by at most max_dt_growth per step so
// that the variable-step Adams-Bashforth coefficients stay well behaved, and capped by dt_max.
// After each step a non-finite velocity or pressure, or a CFL number above cfl_limit (Adams-
// Bashforth 2 is unstable for pure convection beyond CFL of order one), ends the run with a one-line
// finverse::Error that names the step and time, before a blown-up field reaches any output.
#include <cmath>
#include <cstdio>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

double FlowSolver::choose_time_step() const {
  if (opt_.dt > 0) return opt_.dt;
  const double per_dt = cfl(1.0);  // max sum_d |u_d| / h_d
  double dt = per_dt > 0 ? opt_.cfl / per_dt : opt_.dt_max;
  if (dt_old_ > 0) dt = std::min(dt, opt_.max_dt_growth * dt_old_);
  return std::min(dt, opt_.dt_max);
}

void FlowSolver::check_health(double dt, double cfl_now) const {
  double s = norm2(p_);
  for (int c = 0; c < dim(); ++c) s += norm2(u_[static_cast<std::size_t>(c)]);
  char where[96];
  std::snprintf(where, sizeof where, "flow solver: step %ld (t = %.6g s, dt = %.3g s): ", step_, time_, dt);
  if (!std::isfinite(s)) throw Error(std::string(where) + "velocity or pressure is not finite (blow-up)");
  const double c = cfl_now;
  if (c > opt_.cfl_limit) {
    char msg[96];
    std::snprintf(msg, sizeof msg, "CFL number %.3g exceeds the limit %.3g (blow-up; lower dt or cfl)", c,
                  opt_.cfl_limit);
    throw Error(std::string(where) + msg);
  }
}

}  // namespace finverse::cfd
