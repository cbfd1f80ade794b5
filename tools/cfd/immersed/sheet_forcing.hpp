// Direct forcing of a zero-thickness immersed surface (DESIGN.md 5.1; Uhlmann 2005, with the
// markers' coupling of Breugem 2012 solved exactly). After the momentum predictor the impulses g
// solve M g = (U_B - I u*) / dt, M = I S (interpolation times its adjoint spreading), by Jacobi-PCG,
// so u* equals the sheet's velocity at every marker and no marker volume enters. -rho g is the
// force on the fluid band the kernel moves with the sheet; less that band's inertia
// (band_correction) it is the jump across the sheet, the shell's load. All of it is continuous in
// the markers' positions, as no cell changes kind. Why this method and its measurements:
// docs/studies/thin_surface.md.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/delta_kernel.hpp"
#include "cfd/immersed/vec3.hpp"

namespace finverse::cfd {

struct SheetForcingOptions {
  DeltaKernel kernel = DeltaKernel::Smooth3;
  double spacing = 1.0;  // marker spacing, in the grid's cell width at the sheet
  // CG on M g = b: stop at this relative residual or after max_iterations; a residual still above
  // max_residual is an error (the sheet's velocity cannot be imposed). Markers closer together
  // than their kernels can tell apart make M nearly singular; CG from g = 0 then converges on the
  // part of b that M can reach and leaves the near-null force patterns out (they move no fluid),
  // so a modest tolerance is both cheap and what the flow needs.
  double rtol = 1e-6;
  int max_iterations = 300;
  double max_residual = 1e-3;
  // Forcing and projection passes per step: 1, the forcing of u* only (the projection then moves
  // the velocity at the markers by O(dt grad phi)); n > 1, n - 1 more passes of forcing the
  // projected velocity and projecting again, which converge to the velocity that is both
  // solenoidal and equal to the sheet's at the markers (the IB projection method's solution,
  // Taira & Colonius 2007), at one more pressure solve each.
  int projections = 1;
  // Loads: remove the inertia of the fluid band that the kernel moves with the sheet, an added mass
  // a zero-thickness surface does not have (FlowSolver::sheet_loads); false: the markers' impulses
  // as they are. For prescribed motions; inside a partitioned coupling it can leave a light
  // structure a negative effective mass (fin_fsi_run.hpp).
  bool band_correction = true;
};

// The interpolation weights of a set of markers on a grid, over the compact list of the cells they
// touch. Along each axis the kernel's argument is the distance to the cell centre over the width
// of the cell that holds the marker, and the 1-D weights are normalised to sum to 1 (exact on the
// uniform core; on a stretched axis the interpolation of a constant stays exact).
class RegularizedStencils {
 public:
  // periodic[d]: axis d wraps. Throws a one-line finverse::Error naming `what` when a marker is
  // not finite or its kernel reaches past a non-periodic domain boundary.
  RegularizedStencils(const StretchedGrid& grid, const std::array<bool, 3>& periodic, const std::vector<Vec3>& markers,
                      DeltaKernel kernel, const std::string& what);

  std::size_t markers() const { return start_.size() - 1; }
  std::size_t cells() const { return cell_.size(); }
  // (I q)_m for the cell field q.
  void interpolate(const Field& q, std::vector<double>& out) const;
  // q_i += scale * sum_m W_im g_m / V_i.
  void spread(const std::vector<double>& g, double scale, Field& q) const;
  // y = M x.
  void apply(const std::vector<double>& x, std::vector<double>& y) const;
  // M's diagonal.
  std::vector<double> diagonal() const;

 private:
  std::vector<std::array<int, 3>> cell_;  // (i, j, k) of each touched cell
  std::vector<double> inv_volume_;
  std::vector<std::size_t> start_;  // entries of marker m: [start_[m], start_[m + 1])
  std::vector<int> local_;          // entry -> touched cell
  std::vector<double> weight_;
  mutable std::vector<double> work_;
};

struct SheetSolveStats {
  int iterations = 0;  // the largest over the components
  double relative_residual = 0;
};

// g = M^{-1} b by Jacobi-preconditioned CG (g starts at zero). Throws a one-line finverse::Error
// naming `what` when the relative residual stays above opt.max_residual.
SheetSolveStats solve_marker_system(const RegularizedStencils& s, const std::vector<double>& b, std::vector<double>& g,
                                    const SheetForcingOptions& opt, const std::string& what);

}  // namespace finverse::cfd
