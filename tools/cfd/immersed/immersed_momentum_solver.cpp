// Jacobi-preconditioned BiCGSTAB for the momentum system with ghost-cell rows; see
// immersed_momentum_solver.hpp.
#include "cfd/immersed/immersed_momentum_solver.hpp"

#include <cmath>

#include "cfd/grid/grid_loops.hpp"

namespace finverse::cfd {

namespace {
// Helmholtz diagonal of a row: the scale of the ghost and solid rows and the Jacobi preconditioner.
double row_scale(const PoissonOperator& op, double mass, double stiffness, int i, int j, int k) {
  return mass * op.grid().volume(i, j, k) + stiffness * op.diagonal()[op.cell_index(i, j, k)];
}
}  // namespace

void ImmersedMomentumSolver::setup(const StretchedGrid& grid) {
  for (Field* f : {&r_, &r0_, &p_, &v_, &s_, &t_, &ph_, &sh_, &scale_}) *f = Field(grid);
}

void ImmersedMomentumSolver::apply(const HelmholtzSolver& hs, const GhostCellSet& ib, double mass, double stiffness,
                                   Field& x, Field& out) {
  Field scale(hs.op().grid());
  std::vector<std::ptrdiff_t> solid;
  row_scales(hs.op(), ib, mass, stiffness, scale, solid);
  apply_rows(hs, ib, mass, stiffness, scale, solid, x, out);
}

// The rows' scales and the solid cells are fixed during one solve: the operator applications and
// the preconditioner, four per iteration, read them instead of scanning the whole grid for solid
// cells (serially) and recomputing every diagonal each time (perf, Turek-Hron CFD3, 1 thread:
// those two were 6 % of the step).
void ImmersedMomentumSolver::row_scales(const PoissonOperator& op, const GhostCellSet& ib, double mass,
                                        double stiffness, Field& scale, std::vector<std::ptrdiff_t>& solid) {
  const StretchedGrid& g = op.grid();
  for_each_cell(g, [&](int i, int j, int k) { scale(i, j, k) = row_scale(op, mass, stiffness, i, j, k); });
  solid.clear();
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i)
        if (ib.kind(i, j, k) == CellKind::Solid) solid.push_back(scale.index(i, j, k));
}

void ImmersedMomentumSolver::apply_rows(const HelmholtzSolver& hs, const GhostCellSet& ib, double mass,
                                        double stiffness, const Field& scale,
                                        const std::vector<std::ptrdiff_t>& solid, Field& x, Field& out) {
  hs.apply(mass, stiffness, x, out);
  double* o = out.data();
  const double* xs = x.data();
  const double* sc = scale.data();
  for (const std::ptrdiff_t c : solid) o[c] = sc[c] * xs[c];
  for (const GhostCell& gc : ib.ghosts())
    out(gc.i, gc.j, gc.k) = scale(gc.i, gc.j, gc.k) * (x(gc.i, gc.j, gc.k) + gc.dirichlet.apply(x, 0.0));
}

HelmholtzStats ImmersedMomentumSolver::solve(const HelmholtzSolver& hs, const GhostCellSet& ib, double mass, double stiffness, Field& b,
                                             const std::vector<double>& boundary_value, double solid_value, Field& x,
                                             double rtol, int max_iterations) {
  const PoissonOperator& op = hs.op();
  const StretchedGrid& g = op.grid();
  row_scales(op, ib, mass, stiffness, scale_, solid_);
  for (const std::ptrdiff_t c : solid_) b.data()[c] = scale_.data()[c] * solid_value;
  const auto& ghosts = ib.ghosts();
  for (std::size_t n = 0; n < ghosts.size(); ++n) {
    const GhostCell& gc = ghosts[n];
    const double ub = boundary_value.empty() ? 0.0 : boundary_value[n];
    b(gc.i, gc.j, gc.k) = scale_(gc.i, gc.j, gc.k) * (2.0 - gc.dirichlet.boundary_weight) * ub;
  }
  const auto precondition = [&](const Field& in, Field& out) {
    for_each_cell(g, [&](int i, int j, int k) { out(i, j, k) = in(i, j, k) / scale_(i, j, k); });
  };
  const auto matvec = [&](Field& in, Field& out) { apply_rows(hs, ib, mass, stiffness, scale_, solid_, in, out); };
  HelmholtzStats st;
  const double bnorm = norm2(b);
  if (!std::isfinite(bnorm)) {
    st.relative_residual = bnorm;
    return st;
  }
  matvec(x, t_);
  for_each_cell(g, [&](int i, int j, int k) { r_(i, j, k) = b(i, j, k) - t_(i, j, k); });
  double rn = norm2(r_);
  if (bnorm == 0 || rn <= rtol * bnorm) {
    st.converged = true;
    st.relative_residual = bnorm > 0 ? rn / bnorm : 0;
    return st;
  }
  copy_interior(r_, r0_);
  p_.fill(0.0);
  v_.fill(0.0);
  double rho = 1, alpha = 1, omega = 1;
  while (st.iterations < max_iterations) {
    const double rho_new = dot(r0_, r_);
    if (rho_new == 0 || omega == 0) break;  // breakdown
    const double beta = (rho_new / rho) * (alpha / omega);
    rho = rho_new;
    for_each_cell(g, [&](int i, int j, int k) { p_(i, j, k) = r_(i, j, k) + beta * (p_(i, j, k) - omega * v_(i, j, k)); });
    precondition(p_, ph_);
    matvec(ph_, v_);
    const double r0v = dot(r0_, v_);
    if (r0v == 0) break;
    alpha = rho / r0v;
    for_each_cell(g, [&](int i, int j, int k) { s_(i, j, k) = r_(i, j, k) - alpha * v_(i, j, k); });
    ++st.iterations;
    const double sn = norm2(s_);
    if (sn <= rtol * bnorm) {
      axpy(alpha, ph_, x);
      rn = sn;
      break;
    }
    precondition(s_, sh_);
    matvec(sh_, t_);
    const double tt = dot(t_, t_);
    omega = tt > 0 ? dot(t_, s_) / tt : 0.0;
    for_each_cell(g, [&](int i, int j, int k) {
      x(i, j, k) += alpha * ph_(i, j, k) + omega * sh_(i, j, k);
      r_(i, j, k) = s_(i, j, k) - omega * t_(i, j, k);
    });
    rn = norm2(r_);
    if (rn <= rtol * bnorm) break;
  }
  // The true residual, not the recursively updated one.
  matvec(x, t_);
  for_each_cell(g, [&](int i, int j, int k) { r_(i, j, k) = b(i, j, k) - t_(i, j, k); });
  st.relative_residual = norm2(r_) / bnorm;
  st.converged = st.relative_residual <= rtol;
  return st;
}

}  // namespace finverse::cfd
