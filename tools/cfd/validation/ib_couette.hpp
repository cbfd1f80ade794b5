// Circular Couette flow between two immersed concentric circles (radii r1 < r2, centre at the
// origin of the box [-0.6, 0.6]^2): the inner wall turns at Omega, the outer is at rest; the fluid
// between them is found by the ghost-cell immersed boundary on a Cartesian grid that does not
// conform to either circle (the corners outside r2 and the core inside r1 are solid). The steady
// solution of the Navier-Stokes equations is exact,
//     u_theta(r) = A r + B / r,  A = -Omega r1^2 / (r2^2 - r1^2),  B = Omega r1^2 r2^2 / (r2^2 - r1^2),
// so the L2 error of the velocity over the fluid cells measures the order of accuracy of the
// sharp-interface boundary condition on curved walls (issue 4: observed order >= 1.8).
#pragma once

namespace finverse::cfd {

struct IbCouetteSetup {
  int n = 64;                 // cells per side of the box
  double r1 = 0.25, r2 = 0.5, omega = 1.0, nu = 0.05;
  double t_end = 4.0;         // decay of the start-up: exp(-nu (pi / (r2 - r1))^2 t_end) ~ 1e-14
  int polygon_vertices = 1024;
};

struct IbCouetteResult {
  double u_l2 = 0, u_max = 0;  // velocity error over fluid cells (volume-weighted L2, max)
  long steps = 0, ghost_cells = 0;
  double mean_poisson_iterations = 0, mean_momentum_iterations = 0, cpu_seconds = 0;
};

IbCouetteResult run_ib_couette(const IbCouetteSetup& setup);

}  // namespace finverse::cfd
