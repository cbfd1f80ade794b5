// Cell-centred finite-volume discretisation of the variable-coefficient pressure Poisson equation
//
//     div(beta grad p) = f      on a stretched Cartesian grid,
//
// integrated over each cell: sum over faces of beta_f A_f dp/dn = f_P V_P, with the face gradient
// (p_N - p_P) / |x_N - x_P| between neighbouring centres and (p_b - p_P) / (h_P / 2) to a Dirichlet
// wall. The operator is stored as the face transmissibilities T_f = beta_f A_f / d_f of the
// symmetric positive (semi-)definite form
//
//     (A p)_P = sum_f T_f (p_P - p_N) + T_b p_P = b_P,   b_P = -f_P V_P + boundary terms,
//
// i.e. A = -(integrated Laplacian). Second order in L2 and max norm on uniform grids and on grids
// from smooth stretching (the face is then midway between centres up to O(h^2)).
//
// Cells whose faces all have T = 0 (inside an immersed body) are inactive: their row is empty and
// every solver keeps them at zero. The active cells fall into connected components; a component
// that touches no Dirichlet face has the constants as null space, which the solvers handle.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/grid/line_range.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

class PoissonOperator {
 public:
  PoissonOperator() = default;

  // Whether setup() finds the connected components (component(), singular(), the null-space
  // projections below). A solver that handles the null space itself (the MPI ranks' one, with
  // DistributedComponents over the whole grid) skips them: a union-find over every cell, at every
  // set-up of a moving body.
  enum class Connectivity { Build, Skip };

  // Builds transmissibilities, diagonal and connectivity. beta must be >= 0 (checked).
  void setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc,
             Connectivity connectivity = Connectivity::Build);
  // The operator of one MPI rank's block (cells j in [j0, j1), k in [k0, k1) of `whole`; beta on
  // the block's faces, its last face on a periodic axis holding face 0's value): the whole grid's
  // transmissibilities and diagonal bit for bit, so that apply, residual and the smoothers give the
  // whole grid's numbers once the ghosts hold the neighbours' values (cfd/parallel). Block sides
  // inside the domain and periodic y/z sides are Neumann in bc() (their ghosts are the exchange's).
  // No connectivity: a block's own components are not the whole grid's (DistributedComponents).
  void setup_block(const StretchedGrid& whole, const FaceCoefficients& beta, const BoundaryConditions& bc, int j0, int j1,
                   int k0, int k1);

  const StretchedGrid& grid() const { return grid_; }
  const FaceCoefficients& beta() const { return beta_; }
  const BoundaryConditions& bc() const { return bc_; }
  int dim() const { return grid_.dim(); }

  // A field shaped for this operator (one ghost layer).
  Field make_field() const { return Field(grid_, 1); }

  // out = A p with homogeneous boundary conditions. Fills p's ghosts, hence non-const p.
  void apply(Field& p, Field& out) const { apply(p, out, all_lines(grid_)); }
  // The same on `lines` only (out elsewhere untouched), each line's bits as above.
  void apply(Field& p, Field& out, const LineRange& lines) const;
  // r = b - A x.
  void residual(const Field& b, Field& x, Field& r) const;
  // Periodic wrap-around into the ghost layer; ghosts on other sides stay zero, so the stencil
  // realises the homogeneous condition (the inhomogeneous part lives in the right-hand side).
  void fill_ghosts(Field& p) const;

  // b = -f V + sum over Dirichlet faces T_b p_b + sum over Neumann faces beta A dp/dn.
  void assemble_rhs(const Field& f, const BoundaryValues& values, Field& b) const {
    assemble_rhs(f, values, b, all_lines(grid_));
  }
  // The same on `lines` only (b elsewhere untouched).
  void assemble_rhs(const Field& f, const BoundaryValues& values, Field& b, const LineRange& lines) const;

  // The multigrid's coarse operators are rediscretisations of this one: coarsen_operator in
  // coarsening.hpp.

  // Stencil access for smoothers, transfers and the direct coarse solver. Transmissibilities are
  // indexed like FaceCoefficients; for a periodic axis face n(d) duplicates face 0.
  const std::vector<double>& transmissibility(int d) const { return t_[static_cast<std::size_t>(d)]; }
  const std::vector<double>& diagonal() const { return diag_; }
  const std::vector<double>& inverse_diagonal() const { return inv_diag_; }
  std::size_t cell_index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(grid_.nx()) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid_.ny()) * static_cast<std::size_t>(k));
  }
  bool active(int i, int j, int k) const { return diag_[cell_index(i, j, k)] > 0; }
  std::size_t active_cells() const { return active_cells_; }

  // Connectivity: component id per cell (-1 inactive), and whether each component is singular
  // (touches no Dirichlet face, so p is fixed only up to a constant there). It and the projections
  // below throw std::logic_error on an operator set up without it.
  bool has_connectivity() const { return connected_; }
  const std::vector<int>& component() const { return (require_connectivity(), component_); }
  int components() const { return (require_connectivity(), static_cast<int>(singular_.size())); }
  bool singular(int c) const { return (require_connectivity(), singular_[static_cast<std::size_t>(c)] != 0); }
  bool any_singular() const;

  // Null-space handling on singular components:
  // remove the mean (orthogonal projection onto the range of A; used on residuals and on
  // preconditioned vectors),
  void remove_mean(Field& r) const;
  // subtract c_m V from b so that sum b = 0 on each component (a uniform shift of the source f:
  // the compatibility projection of the right-hand side),
  void make_compatible(Field& b) const;
  // subtract the volume-weighted mean of p (fixes the free constant).
  void remove_volume_mean(Field& p) const;
  // Keeps inactive cells at exactly zero.
  void zero_inactive(Field& x) const;

 private:
  void build(const StretchedGrid& whole, const BoundaryConditions& bc, std::array<int, 3> offset);
  void build_connectivity();
  void require_connectivity() const;
  bool single_open_component();

  StretchedGrid grid_;
  FaceCoefficients beta_;
  BoundaryConditions bc_;
  std::array<std::vector<double>, 3> t_;
  std::vector<double> diag_, inv_diag_;
  std::size_t active_cells_ = 0;
  std::vector<int> component_;
  std::vector<char> singular_;
  bool connected_ = false;
};

}  // namespace finverse::cfd
