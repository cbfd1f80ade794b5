// The Crank-Nicolson momentum system of one velocity component with the sharp-interface
// immersed boundary (Mittal et al. 2008, section 2.3): the rows of fluid cells are the Helmholtz
// operator of helmholtz_solver.hpp (fluid cells reach their ghost neighbours through ordinary
// faces), the rows of ghost cells impose the Dirichlet velocity at the boundary intercept through
// the image point,
//
//     D_G (u_G + sum_k w_k u_k) = D_G (2 - w_B) u_B,     (u_G + u_I = 2 u_B, ghost_cells.hpp)
//
// and the rows of the remaining solid cells pin u = u_body. D is the Helmholtz diagonal of the
// row, so all rows have the same scale and the Jacobi preconditioner is the same as for the plain
// system.
//
// The ghost rows make the matrix nonsymmetric (u_G depends on the image stencil's fluid cells, not
// the other way round), so conjugate gradients is not applicable. BiCGSTAB (van der Vorst 1992)
// with the Jacobi preconditioner: short recurrences (memory and cost as CG's, two operator
// applications per iteration), no restart parameter to tune as GMRES(m), and it converges in a few
// tens of iterations because the system is a diagonally dominant Helmholtz matrix plus a small
// number of nonsymmetric ghost rows with the weights of an interpolation. Gauss-Seidel on the
// whole system would also converge, but needs O(nu dt / h^2) sweeps and is sequential.
// All reductions are ordered (field.hpp): the iteration is bitwise independent of the threads.
#pragma once

#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/flow/helmholtz_solver.hpp"

namespace finverse::cfd {

class ImmersedMomentumSolver {
 public:
  // Work vectors for the grid. The Helmholtz solver passed to solve() supplies the fluid rows (its
  // operator must be unmasked: beta = 1 on the faces to ghost cells).
  void setup(const StretchedGrid& grid);

  // Solves the system to ||r|| <= rtol ||b||. b holds the fluid rows' right-hand side (its ghost
  // and solid rows are overwritten); boundary_value[g] is u_B of ghost cell g (empty: 0);
  // solid_value pins the solid cells; x holds the initial guess.
  HelmholtzStats solve(const HelmholtzSolver& helmholtz, const GhostCellSet& ghosts, double mass, double stiffness, Field& b, const std::vector<double>& boundary_value,
                       double solid_value, Field& x, double rtol, int max_iterations);

  // out = M x (all rows); fills x's ghosts.
  static void apply(const HelmholtzSolver& helmholtz, const GhostCellSet& ghosts, double mass, double stiffness,
                    Field& x, Field& out);

 private:
  // scale = every row's Helmholtz diagonal; solid = the Field indices of the solid cells.
  static void row_scales(const PoissonOperator& op, const GhostCellSet& ghosts, double mass, double stiffness,
                         Field& scale, std::vector<std::ptrdiff_t>& solid);
  // apply() with the scales and solid cells of row_scales().
  static void apply_rows(const HelmholtzSolver& helmholtz, const GhostCellSet& ghosts, double mass, double stiffness,
                         const Field& scale, const std::vector<std::ptrdiff_t>& solid, Field& x, Field& out);

  Field r_, r0_, p_, v_, s_, t_, ph_, sh_;
  Field scale_;                       // row scales of the current solve
  std::vector<std::ptrdiff_t> solid_;  // its solid cells
};

}  // namespace finverse::cfd
