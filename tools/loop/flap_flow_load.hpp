// The 3-D flow's load on the Hessenthaler flap near its Phase I steady state, as a function of the
// flap's tip (issue 49, deliverable 4). fin-fsi flap --loads writes every evaluation of its root
// search: the tip it held the flap at and the flow's time-mean nodal load there (flap_loads.h5).
// Near the root the load changes steeply with the tip (the tip meets the edge of the +y jet), so a
// structural change that moves the flap also moves its load: a dead load would overstate every
// candidate's effect ~20-fold. The load is therefore taken as linear in the tip,
//     F(t) = F0 + (t - t0) dF/dt,
// least squares over the evaluations within `window` of the root (at least the two nearest), the
// flap then sitting where tip(S(F(t))) = t. Flow-side errors come from runs with a perturbed
// viscosity or inflow: their own F(t) minus the base's, per unit of the factor's change.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace finverse::loop {

struct FlapFlowLoad {
  std::filesystem::path source;
  double tip0 = 0;                    // the root's held tip [m]
  Eigen::VectorXd load0, slope;       // F(t0) [N] and dF/dt [N/m], 3 per shell node, flap frame
  double viscosity_factor = 1, inflow_factor = 1, youngs_modulus = 0, h = 0;
  int along = 0, across = 0;          // the shell strip the loads are on
  int evaluations_used = 0;
  Eigen::VectorXd at(double tip) const { return load0 + (tip - tip0) * slope; }
};

// Reads fin-fsi flap's flap_loads.h5. Throws InvalidInput naming the file and what is wrong (not
// the schema, fewer than two evaluations, a load that does not match the strip).
FlapFlowLoad read_flap_flow_load(const std::filesystem::path& path, double window = 4e-3);

}  // namespace finverse::loop
