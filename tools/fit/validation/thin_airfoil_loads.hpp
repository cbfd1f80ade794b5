// Known hydrodynamic loads for the plate twins of the fit validation (issue 31): the pressure
// jump of a rigid flat plate in heave h(t) and pitch theta(t) about its leading edge, from
// quasi-steady thin-airfoil theory plus the added-mass pressure (Theodorsen's terms with
// C(k) = 1, no wake), lumped onto the shell nodes. The twin needs loads that are known, smooth
// and shaped like a plate's (leading-edge suction peak, added mass near mid-chord), not exact
// hydrodynamics; the fin-cfd loads replace them when run (the issue's "loads from fin-cfd on the
// rigid or prescribed motion").
//
// Plate normal velocity (positive +y) v(x) = hdot - x thetadot - U theta = v0 + v1 (x - c/2);
// x = c/2 (1 - cos phi): A0 = -v0/U, A1 = -v1 c/(2U); pressure jump along +y
//   dp(x) = 2 rho U^2 [A0 cot(phi/2) + A1 sin(phi)] - rho [2 dv0/dt sqrt(x(c-x)) + dv1/dt xi sqrt(b^2 - xi^2)]
// with xi = x - c/2, b = c/2. Lift per span = pi rho U^2 c (A0 + A1/2) - (added mass).
#pragma once

#include <functional>
#include <vector>

#include "fem/load_history.hpp"
#include "fem/model.hpp"

namespace finverse::fit::validation {

struct RigidPlateMotion {
  // h, dh/dt, d2h/dt2 [length, length/time, ...] and theta, dtheta/dt, d2theta/dt2 [rad] (nose up
  // positive: y = h - x theta); empty functions are zero.
  std::function<double(double)> h, hdot, hddot, theta, thetadot, thetaddot;
};

struct ThinAirfoilFlow {
  double rho = 1, speed = 1, chord = 1;
  double leading_edge_x = 0;  // the plate lies in the x-z plane from x = leading_edge_x
};

// Pressure jump along +y at chord position x (0 < x < chord) and time t.
double thin_airfoil_pressure(const ThinAirfoilFlow& flow, const RigidPlateMotion& motion, double x, double t);

// Nodal forces (y component) on every three-node element of the model (the shell triangles) at
// the given times, integrated with an interior 3-point rule per triangle (no node sits on the
// leading-edge singularity). ramp as LoadHistory's.
fem::LoadHistory thin_airfoil_loads(const fem::Model& model, const ThinAirfoilFlow& flow,
                                    const RigidPlateMotion& motion, const std::vector<double>& times,
                                    double ramp = 0);

}  // namespace finverse::fit::validation
