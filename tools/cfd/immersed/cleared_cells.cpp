// Freshly cleared cells of a moving immersed body (Mittal et al. 2008, J. Comput. Phys. 227:4825,
// section 2.4), the part shared by the 2-D polygon (moving_body.cpp) and the 3-D triangulated
// surface (moving_surface.cpp): once each cleared cell has its line from the boundary intercept B
// to P = x + 1.5 h n (ClearedCell, built by the caller from its own geometry), the cleared values
//     u(x) = u_B + (u(P) - u_B) d / (d + 1.5 h),     p(x) = p(P) - 1.5 h dp/dn(B)
// and the ghost values of the new geometry are iterated together (P's stencil may hold ghost cells
// and other cleared cells; the weights are those of an interpolation, so a few rounds suffice),
// and the cleared cells' faces, body faces at t^n, get fluid fluxes for their first N^n.
// The ghost values imposed here serve the cleared cells' stencils and the implicit part of the
// step; the explicit terms act on u^n, so afterwards every ghost cell of the new geometry that was
// a fluid or ghost cell at t^n gets its u^n back (flow_solver.hpp: re-imposed for the body's new
// position they would move the wall by U dt within the explicit terms). Cells that were solid at
// t^n keep the new ghost values: they had no value the fluid saw.
#include <array>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

void FlowSolver::settle_cleared_cells(const GhostCellSet& old, const std::vector<ClearedCell>& cells) {
  std::vector<std::array<int, 3>> kept;
  std::vector<double> kept_u;
  // The ghost list, not a scan of the grid: this runs every step of a moving body.
  for (const GhostCell& g : ib_->ghosts())
    if (old.kind(g.i, g.j, g.k) != CellKind::Solid) {
      kept.push_back({g.i, g.j, g.k});
      for (int c = 0; c < dim(); ++c) kept_u.push_back(u_[static_cast<std::size_t>(c)](g.i, g.j, g.k));
    }
  if (!cells.empty()) {
    for (int round = 0; round < 4; ++round) {
      for (std::size_t n = 0; n < cells.size(); ++n) {
        const auto& f = fresh_[n];
        const ClearedCell& e = cells[n];
        for (int c = 0; c < dim(); ++c) {
          Field& u = u_[static_cast<std::size_t>(c)];
          const double ub = e.ub[static_cast<std::size_t>(c)];
          u(f[0], f[1], f[2]) = ub + (e.vel.apply(u, ub) - ub) * e.fraction;
        }
        p_(f[0], f[1], f[2]) = e.pres.apply(p_, e.dpdn) - e.offset * e.dpdn;
      }
      impose_body_velocity();
      ib_->impose_neumann(p_, ib_dpdn_);
    }
  } else {
    impose_body_velocity();
    ib_->impose_neumann(p_, ib_dpdn_);
  }
  ib_->impose_neumann(phi_);
  for (std::size_t n = 0, m = 0; n < kept.size(); ++n)
    for (int c = 0; c < dim(); ++c) u_[static_cast<std::size_t>(c)](kept[n][0], kept[n][1], kept[n][2]) = kept_u[m++];
  if (!opt_.fresh_cell_treatment) return;
  // The interpolation of the (cleared and ghost) cell values, as for the fluid faces of U*.
  for (const auto& f : fresh_)
    for (int d = 0; d < dim(); ++d)
      for (int side = 0; side < 2; ++side) {
        int idx[3] = {f[0], f[1], f[2]};
        idx[d] += side;
        const int m = idx[d];
        if ((m == 0 || m == grid_.n(d)) && !bnd_.periodic(d)) continue;
        U_(d, idx[0], idx[1], idx[2]) = face_value(u_[static_cast<std::size_t>(d)], d, d, idx[0], idx[1], idx[2], bv_);
      }
}

}  // namespace finverse::cfd
