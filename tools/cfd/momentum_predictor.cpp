// Step 1 of the fractional step (Van Kan 1986): the intermediate velocity u* from
//
//   V (u* - u^n)/dt = -V [(1 + r/2) N^n - (r/2) N^{n-1}] - V Gc p^n + V f^{n+1/2}
//                     + nu/2 [(-A u* + b^{n+1}) + (-A u^n + b^n)],        r = dt / dt_old,
//
// i.e. Adams-Bashforth 2 for convection (second order with variable steps; r = 0, explicit Euler,
// on the first step) and Crank-Nicolson for diffusion, where -A u + b is the volume-integrated
// finite-volume Laplacian with the boundary values b of that time level. The convective term is
// conservative, N = (1/V) sum_f (U_f A_f) u_f, with the solenoidal face velocities U^n and
// linearly interpolated face values u_f: it conserves momentum exactly in a periodic box and, on a
// uniform grid, kinetic energy too (skew-symmetric for a divergence-free U). With an immersed body
// the ghost and solid rows of the implicit system carry the body's velocity condition
// (immersed_momentum_solver.hpp); the explicit terms of fluid cells next to the body use the ghost
// values of u^n and p^n, which hold the sharp boundary conditions.
#include "cfd/flow_solver.hpp"
#include "cfd/loops.hpp"
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

void FlowSolver::convective_term(std::array<Field, 3>& out) const {
  for (int c = 0; c < dim(); ++c) {
    const Field& q = u_[static_cast<std::size_t>(c)];
    Field& o = out[static_cast<std::size_t>(c)];
    for_each_cell(grid_, [&](int i, int j, int k) {
      double s = 0;
      for (int d = 0; d < dim(); ++d) {
        int h[3] = {i, j, k};
        ++h[d];
        const double A = face_area(d, i, j, k);
        s += A * (U_(d, h[0], h[1], h[2]) * face_value(q, c, d, h[0], h[1], h[2], bv_) -
                  U_(d, i, j, k) * face_value(q, c, d, i, j, k, bv_));
      }
      o(i, j, k) = s / grid_.volume(i, j, k);
    });
  }
}

void FlowSolver::predict_momentum(double dt) {
  if (opt_.convection) convective_term(conv_);
  else
    for (int c = 0; c < dim(); ++c) conv_[static_cast<std::size_t>(c)].fill(0.0);
  // A freshly cleared cell has no N^{n-1} of its own (its stored value is a ghost cell's or a
  // solid cell's): Adams-Bashforth falls back to explicit Euler there for this step.
  if (opt_.fresh_cell_treatment)
    for (const auto& f : fresh_)
      for (int c = 0; c < dim(); ++c)
        conv_old_[static_cast<std::size_t>(c)](f[0], f[1], f[2]) = conv_[static_cast<std::size_t>(c)](f[0], f[1], f[2]);
  const double r = dt_old_ > 0 ? dt / dt_old_ : 0.0;
  const double ab_new = 1 + 0.5 * r, ab_old = -0.5 * r;
  const double half_nu = 0.5 * opt_.nu;
  const double t_half = time_ + 0.5 * dt;
  last_helmholtz_iterations_ = 0;
  for (int c = 0; c < dim(); ++c) {
    const auto C = static_cast<std::size_t>(c);
    HelmholtzSolver& hs = helmholtz_[C];
    Field& un = u_[C];
    cell_gradient(p_, c, grad_);
    hs.op().apply(un, work_[C]);  // A u^n
    // Boundary terms of both time levels (Dirichlet: T_b u_b).
    hs.op().assemble_rhs(zero_, bv_[C], rhs_);
    hs.op().assemble_rhs(zero_, bv_new_[C], bterm_);
    const Field& n_new = conv_[C];
    const Field& n_old = conv_old_[C];
    const Field& A_un = work_[C];
    for_each_cell(grid_, [&](int i, int j, int k) {
      const double V = grid_.volume(i, j, k);
      double force = 0;
      if (opt_.body_force)
        force = opt_.body_force(grid_.xc(i), grid_.yc(j), grid_.zc(k), t_half)[C];
      const double explicit_part = un(i, j, k) / dt - (ab_new * n_new(i, j, k) + ab_old * n_old(i, j, k)) -
                                   grad_(i, j, k) + force;
      rhs_(i, j, k) = V * explicit_part + half_nu * (-A_un(i, j, k) + rhs_(i, j, k) + bterm_(i, j, k));
    });
    Field& us = ustar_[C];
    copy_interior(un, us);
    const HelmholtzStats st =
        ib_ ? ib_momentum_.solve(hs, *ib_, 1.0 / dt, half_nu, rhs_, ib_wall_[C], 0.0, us, opt_.helmholtz_rtol,
                                 opt_.helmholtz_max_iterations)
            : hs.solve(1.0 / dt, half_nu, rhs_, us, opt_.helmholtz_rtol, opt_.helmholtz_max_iterations);
    if (!std::isfinite(st.relative_residual))
      throw Error("flow solver: step " + std::to_string(step_ + 1) + ": momentum right-hand side of component " +
                  std::to_string(c) + " is not finite (blow-up)");
    if (!st.converged)
      throw Error("flow solver: step " + std::to_string(step_ + 1) + ": momentum solve of component " +
                  std::to_string(c) + " did not converge (relative residual " + std::to_string(st.relative_residual) +
                  " after " + std::to_string(st.iterations) + " iterations)");
    last_helmholtz_iterations_ += st.iterations;
  }
}

}  // namespace finverse::cfd
