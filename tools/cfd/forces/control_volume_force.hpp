// Hydrodynamic force on a fixed immersed body from the momentum balance of a rectangular control
// volume V around it (a box in 3-D): an independent check of the surface traction
// (surface_traction.hpp, surface_traction_3d.hpp). Integrating the momentum equation over the
// fluid in V (Gauss) gives the force (2-D: per unit depth)
//
//     F = -rho [ d/dt int_V u dV + oint_S ( u (u . n) + p n - nu du/dn ) dS ],
//
// S the rectangle's (box's) outer boundary with outward normal n, p kinematic. The transposed
// part of the viscous stress, nu (grad u)^T n, is left out on S because it is left out on the body:
// its integral over the closed fluid boundary is that of grad(div u) = 0, and on a resting no-slip
// wall it vanishes pointwise (tangential derivatives of u are zero, n . du/dn = 0 by continuity).
// The rectangle is snapped to cell faces; on them u (u . n) uses the solver's face-normal
// velocity U (the conservative flux) and the linearly interpolated cell value of u, p is
// interpolated linearly, du/dn is the compact difference of the two neighbouring centres. The
// volume integral sums V_c u_c over the fluid cells (ghost and solid cells hold no fluid
// momentum; cut cells contribute only where u is small, next to the wall). The time derivative is
// taken from the recorded series by central differences (control_volume_forces).
// The two measurements agree when the traction evaluation is right; where they disagree the
// surface evaluation (probes, extrapolation, corners), not the flow, is at fault.
#pragma once

#include <array>
#include <vector>

#include "cfd/grid/face_field.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

// One instant: the fluid momentum in V and the surface integral over S (both kinematic, per rho;
// 2-D: the z components 0).
struct ControlVolumeSample {
  double t = 0;
  std::array<double, 3> momentum{}, flux{};
};

class ControlVolumeForce {
 public:
  // Rectangle [x0, x1] x [y0, y1] of a 2-D grid, or box {x0, x1, y0, y1, z0, z1} of a 3-D one,
  // snapped to the nearest cell faces; it must hold the body with at least two fluid cells to
  // spare on every side. Throws finverse::Error otherwise. ghosts must outlive this object.
  ControlVolumeForce(const StretchedGrid& grid, const GhostCellSet& ghosts, double x0, double x1, double y0, double y1);
  ControlVolumeForce(const StretchedGrid& grid, const GhostCellSet& ghosts, const std::array<double, 6>& box);

  // The snapped rectangle's faces: cells [i0, i1) x [j0, j1) (3-D: also [k0, k1), cells_z()).
  std::array<int, 4> cells() const { return {lo_[0], hi_[0], lo_[1], hi_[1]}; }
  std::array<int, 2> cells_z() const { return {lo_[2], hi_[2]}; }

  // u, v (w): cell velocities; U: face-normal velocities; p: kinematic pressure.
  ControlVolumeSample evaluate(double t, const Field& u, const Field& v, const FaceField& U, const Field& p,
                               double nu) const;
  ControlVolumeSample evaluate(double t, const Field& u, const Field& v, const Field& w, const FaceField& U,
                               const Field& p, double nu) const;

 private:
  ControlVolumeSample integrate(double t, const std::array<const Field*, 3>& q, const FaceField& U, const Field& p,
                                double nu) const;

  StretchedGrid grid_;
  const GhostCellSet* ghosts_;
  std::array<int, 3> lo_{}, hi_{};  // faces along x, y, z (2-D: z 0 .. 1)
};

// Force [N] (2-D: per unit depth, N/m) at every sample, -rho (dM/dt + flux), dM/dt by central
// differences (one-sided at the ends). Needs at least two samples with increasing times.
std::vector<std::array<double, 3>> control_volume_forces(const std::vector<ControlVolumeSample>& samples, double rho);

}  // namespace finverse::cfd
