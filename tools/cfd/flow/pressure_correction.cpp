// Step 2 of the fractional step: the face predictor and the pressure-correction Poisson equation.
//
// Face predictor (Zang, Street & Koseff 1994, with the incremental pressure of Van Kan 1986):
//     U*_f = I_f(u* + tau Gc q) - tau Gf q,
// the interpolation of the cell velocity with a cell-centred pressure gradient swapped for the
// compact face gradient: the face velocity feels the pressure through the two cells it separates,
// which suppresses the odd-even decoupling of collocated grids (the idea of Rhie & Chow 1983). The
// faces then differ from the interpolated cells by D = U - I(u), a pressure term of size O(tau h^2):
//   - classical form (coupling_time = 0): tau = dt, q = p^n, i.e. U* = I(u* + dt Gc p^n) - dt Gf p^n.
//     Then D = dt (I Gc - Gf) p^{n+1/2}, an O(dt h^2) term: on a fixed grid the error is first
//     order in dt (small, but it dominates a temporal convergence study). A checkerboard mode of p
//     is removed in one step.
//   - fixed coupling time tau (clamped to <= dt/2): q = p^n + (3/2 - dt/tau) (dt/dt_old) phi^n
//     extrapolates the pressure so that D^{n+1} = tau (I Gc - Gf) p(t^{n+1}) + O(tau dt^2 h^2): a
//     purely spatial O(h^2) term at the right time level, and the error is O(h^2) + O(dt^2).
//     A checkerboard mode is damped by sqrt(1 - 3 tau / (2 dt)) per step (stable for
//     tau/dt < 0.64 with complex roots; hence the clamp).
// Boundary faces carry the prescribed fluxes (boundary_update.cpp).
//
// Correction: phi = p^{n+1/2} - p^{n-1/2} from  Df Gf phi = Df U* / dt  with homogeneous Neumann
// conditions on non-periodic sides, by MG-PCG warm-started from the previous step's phi. With an
// immersed body the faces of non-fluid cells are closed (flow_solver.hpp): they keep the
// interpolated face velocity of u*, and phi gets its ghost values from the Neumann condition.
#include <algorithm>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/grid/grid_loops.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

double FlowSolver::coupling_time(double dt) const {
  return opt_.coupling_time > 0 ? std::min(opt_.coupling_time, 0.5 * dt) : dt;
}

void FlowSolver::face_predictor(double dt, double tau) {
  const double extrapolate =
      opt_.coupling_time > 0 && dt_old_ > 0 ? (1.5 - dt / tau) * (dt / dt_old_) : 0.0;
  Field& q = rhs_;
  for_each_cell(grid_, [&](int i, int j, int k) { q(i, j, k) = p_(i, j, k) + extrapolate * phi_(i, j, k); });
  for (int d = 0; d < dim(); ++d) {
    const auto D = static_cast<std::size_t>(d);
    cell_gradient(q, d, grad_);
    Field& w = work_[D];
    const Field& us = ustar_[D];
    for_each_cell(grid_, [&](int i, int j, int k) { w(i, j, k) = us(i, j, k) + tau * grad_(i, j, k); });
    const int n = grid_.n(d);
    const bool periodic = bnd_.periodic(d);
    for_each_face(grid_, d, faces_, [&](int i, int j, int k) {  // (the rank's own lines: rank_lines.cpp)
      const int f = d == 0 ? i : d == 1 ? j : k;
      if (!periodic && (f == 0 || f == n)) return;  // prescribed boundary flux
      if (masked_face(d, i, j, k)) return;             // immersed body: body_face_velocities
      Ustar_(d, i, j, k) = face_value(w, d, d, i, j, k, bv_new_) - tau * face_gradient(q, d, i, j, k);
    });
  }
  if (ib_) body_face_velocities(Ustar_, ustar_);
}

PoissonSolveStats FlowSolver::solve_pressure_correction(double dt) {
  if (pressure_stale_) setup_pressure_operator();
  // (on MPI ranks the system reads only the rank's block of it: computed there alone)
  for_each_cell(grid_, poisson_.rhs_lines(),
                [&](int i, int j, int k) { rhs_(i, j, k) = continuity_residual(Ustar_, i, j, k) / dt; });
  const PoissonSolveStats st = poisson_.solve(rhs_, BoundaryValues{}, phi_);
  // The cut faces are corrected with phi as solved (update_velocity); the cell-centred gradients
  // take the ghost values of the Neumann condition dphi/dn = 0 at the boundary intercept.
  if (cut_) copy_interior(phi_, phi_solved_);
  if (ib_) ib_->impose_neumann(phi_);
  if (!st.converged)
    throw Error("flow solver: step " + std::to_string(step_ + 1) + ": pressure-correction solve did not converge (" +
                std::to_string(st.iterations) + " iterations, relative residual " +
                std::to_string(st.relative_residual) + ")");
  return st;
}

}  // namespace finverse::cfd
