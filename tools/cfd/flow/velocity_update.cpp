// Step 3 of the fractional step: the projection onto (discretely) divergence-free faces,
//     U^{n+1} = U* - dt Gf phi,   u^{n+1} = u* - dt Gc phi,
//     p^{n+1/2} = p^{n-1/2} + phi      (Van Kan; the pressure lives at the Crank-Nicolson half steps;
// FlowSolver::pressure() adds the Brown-Cortez-Minion term for output).
// Df Gf is exactly the Poisson operator that phi solved, so Df U^{n+1} = 0 to the solver tolerance;
// the cell velocities are corrected with the cell-centred gradient (Zang, Street & Koseff 1994) and
// are divergence-free only to truncation error, as on every collocated grid. On non-periodic sides
// Gf phi = 0 (homogeneous Neumann), so the prescribed boundary fluxes are kept; so are the fluxes
// on the closed faces of an immersed body, whose ghost cells then get the velocity condition again.
// With the cut-cell balance a face with fluid on it is corrected by alpha dt Gf phi: it then stores
// the mean velocity over the whole face, alpha times the fluid part's U* - dt Gf phi plus (1 - alpha)
// times U* for the solid part, which moves with the wall. The fluid part's own velocity is large in
// a cell with a tiny fluid part whose wall velocity varies (its volume changes fast and feeds
// through a tiny aperture); the momentum equations' convective fluxes take the full face, and the
// mean keeps them bounded. (The blow-ups of thin plates were cured by keeping faces between fluid
// cells whole, cut_cell_balance.cpp, not by this: docs/studies/cut_cell_balance.md.)
#include <algorithm>
#include <cmath>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/grid/grid_loops.hpp"

namespace finverse::cfd {

namespace {
// fn(i, j, k) for the faces normal to d on the domain's two sides across d.
template <class Fn>
void boundary_faces(const StretchedGrid& g, int d, Fn fn) {
  const int n[3] = {g.nx(), g.ny(), g.nz()};
  const int a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;  // the tangential axes
  for (int f : {0, n[d]})
    for (int q = 0; q < n[b]; ++q)
      for (int p = 0; p < n[a]; ++p) {
        int x[3];
        x[d] = f, x[a] = p, x[b] = q;
        fn(x[0], x[1], x[2]);
      }
}
}  // namespace

void FlowSolver::update_velocity(double dt) {
  for (int d = 0; d < dim(); ++d) {
    const auto D = static_cast<std::size_t>(d);
    if (cut_) {  // every face with fluid on it, with phi as solved (also in the cut ghost cells)
      for_each_face(grid_, d, [&](int i, int j, int k) {
        const double alpha = cut_->aperture(d, i, j, k);
        U_(d, i, j, k) = Ustar_(d, i, j, k) - (alpha > 0 ? alpha * dt * face_gradient(phi_solved_, d, i, j, k) : 0.0);
      });
    } else {
      const auto update = [&](int i, int j, int k) {
        U_(d, i, j, k) = Ustar_(d, i, j, k) - (masked_face(d, i, j, k) ? 0.0 : dt * face_gradient(phi_, d, i, j, k));
      };
      for_each_face(grid_, d, faces_, update);  // (the rank's own lines: rank_lines.cpp)
      // and the domain's boundary faces on every line: the outlet's flux balance sums them all
      if (!(faces_ == all_lines(grid_)) && !bnd_.periodic(d)) boundary_faces(grid_, d, update);
    }
    cell_gradient(phi_, d, grad_);
    Field& u = u_[D];
    const Field& us = ustar_[D];
    for_each_cell(grid_, [&](int i, int j, int k) { u(i, j, k) = us(i, j, k) - dt * grad_(i, j, k); });
  }
  if (cut_) {
    // The balance itself, with the fluid parts' velocities U* - dt Gf phi (the stored faces carry
    // their aperture-weighted mean, above), for max_divergence().
    cut_residual_max_ = 0;
    const auto fluid_part = [&](int d, int i, int j, int k) {
      return Ustar_(d, i, j, k) - dt * face_gradient(phi_solved_, d, i, j, k);
    };
    for (std::size_t n = 0; n < cut_cells_.size(); ++n) {
      const auto [i, j, k] = cut_cells_[n];
      cut_residual_max_ = std::max(cut_residual_max_, std::abs(cut_balance(n, fluid_part)) / grid_.volume(i, j, k));
    }
  }
  for_each_cell(grid_, [&](int i, int j, int k) { p_(i, j, k) += phi_(i, j, k); });
  if (ib_) {
    impose_body_velocity();
    if (wall_dpdn_) ib_dpdn_ = wall_dpdn_->evaluate(u_[0], u_[1], opt_.nu);
    if (wall_dpdn_3d_) ib_dpdn_ = wall_dpdn_3d_->evaluate(u_[0], u_[1], u_[2], opt_.nu);
    ib_->impose_neumann(p_, ib_dpdn_);
  }
}

}  // namespace finverse::cfd
