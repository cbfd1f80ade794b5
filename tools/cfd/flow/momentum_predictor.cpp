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
#include "cfd/flow/flow_solver.hpp"
#include "cfd/grid/grid_loops.hpp"
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace finverse::cfd {

// N one grid line (j, k) at a time: the face fluxes U_f u_f of the line's x faces once each, and
// those of its lower and upper y and z faces in contiguous rows, so the inner loops vectorise. Each
// cell's sum is the same expression, in the same order, as a cell-by-cell evaluation with
// face_value (the boundary faces use it), so the bits do not depend on the loop's shape.
void FlowSolver::convective_term(std::array<Field, 3>& out) const {
  const int D = dim(), nx = grid_.nx();
  // Weight of the lower cell at each interior face (as face_value).
  std::array<std::vector<double>, 3> lower_weight;
  for (int d = 0; d < D; ++d) {
    const Axis& ax = grid_.axis(d);
    auto& w = lower_weight[static_cast<std::size_t>(d)];
    w.assign(static_cast<std::size_t>(ax.size()) + 1, 0.0);
    for (int f = 1; f < ax.size(); ++f) w[static_cast<std::size_t>(f)] = ax.lower_weight(f);
  }
  for (int c = 0; c < D; ++c) {
    const Field& q = u_[static_cast<std::size_t>(c)];
    Field& o = out[static_cast<std::size_t>(c)];
    // dst[i] = U_f u_f on the faces normal to d (d = 1, 2) at row (fj, fk).
    const auto face_row = [&](int d, int fj, int fk, double* dst) {
      const double* U = U_.values(d).data() + U_.index(d, 0, fj, fk);
      const int f = d == 1 ? fj : fk;
      if (f <= 0 || f >= grid_.axis(d).size()) {
        for (int i = 0; i < nx; ++i) dst[i] = U[i] * boundary_face_value(q, c, d, i, fj, fk, bv_);
        return;
      }
      const double w = lower_weight[static_cast<std::size_t>(d)][static_cast<std::size_t>(f)];
      const double* lo = &q(0, fj - (d == 1), fk - (d == 2));
      const double* hi = &q(0, fj, fk);
      for (int i = 0; i < nx; ++i) dst[i] = U[i] * (w * lo[i] + (1 - w) * hi[i]);
    };
    for_each_line(grid_, own_, [&](int j, int k) {  // (the rank's own lines: rank_lines.cpp)
      thread_local std::vector<double> buf;
      buf.resize(5 * static_cast<std::size_t>(nx) + 1);
      double* fx = buf.data();
      double* row[2][2] = {{fx + nx + 1, fx + 2 * nx + 1}, {fx + 3 * nx + 1, fx + 4 * nx + 1}};
      const double* Ux = U_.values(0).data() + U_.index(0, 0, j, k);
      const double* qa = &q(0, j, k);
      const double* wx = lower_weight[0].data();
      fx[0] = Ux[0] * boundary_face_value(q, c, 0, 0, j, k, bv_);
      fx[nx] = Ux[nx] * boundary_face_value(q, c, 0, nx, j, k, bv_);
      for (int f = 1; f < nx; ++f) fx[f] = Ux[f] * (wx[f] * qa[f - 1] + (1 - wx[f]) * qa[f]);
      for (int d = 1; d < D; ++d) {
        face_row(d, j, k, row[d - 1][0]);
        face_row(d, j + (d == 1), k + (d == 2), row[d - 1][1]);
      }
      const double Ax = face_area(0, 0, j, k);
      double* oa = &o(0, j, k);
      for (int i = 0; i < nx; ++i) {
        double s = 0;
        s += Ax * (fx[i + 1] - fx[i]);
        for (int d = 1; d < D; ++d) s += face_area(d, i, j, k) * (row[d - 1][1][i] - row[d - 1][0][i]);
        oa[i] = s / grid_.volume(i, j, k);
      }
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
    // On MPI ranks the momentum system reads only the rank's block of the right-hand side, so its
    // terms are computed there alone; a closed body's ghost-cell rows are solved whole.
    const LineRange lines = ib_ ? all_lines(grid_) : hs.rhs_lines();
    cell_gradient(p_, c, grad_, lines);
    hs.op().apply(un, work_[C], lines);  // A u^n
    // Boundary terms of both time levels (Dirichlet: T_b u_b).
    hs.op().assemble_rhs(zero_, bv_[C], rhs_, lines);
    hs.op().assemble_rhs(zero_, bv_new_[C], bterm_, lines);
    const Field& n_new = conv_[C];
    const Field& n_old = conv_old_[C];
    const Field& A_un = work_[C];
    for_each_cell(grid_, lines, [&](int i, int j, int k) {
      const double V = grid_.volume(i, j, k);
      double force = 0;
      if (opt_.body_force)
        force = opt_.body_force(grid_.xc(i), grid_.yc(j), grid_.zc(k), t_half)[C];
      const double explicit_part = un(i, j, k) / dt - (ab_new * n_new(i, j, k) + ab_old * n_old(i, j, k)) -
                                   grad_(i, j, k) + force;
      rhs_(i, j, k) = V * explicit_part + half_nu * (-A_un(i, j, k) + rhs_(i, j, k) + bterm_(i, j, k));
    });
    Field& us = ustar_[C];
    copy_interior(repeating_ ? solved_ustar_[C] : un, us);
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
    if (warm_start_repeats_) copy_interior(us, solved_ustar_[C]);
  }
}

}  // namespace finverse::cfd
