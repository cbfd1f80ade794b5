// Principal spatial modes of the residual (issue 34; DESIGN.md section 5.6): proper orthogonal
// decomposition by the thin SVD of the node-weighted residual matrix,
//     diag(sqrt w) R = U S V^T,   R [3 nv, nf],
// so mode m has the spatial shape phi_m = U_m / sqrt(w) (per node, 3 components), the time
// coefficient a_m(t) = s_m V_m(t) and the energy fraction s_m^2 / sum s^2. The weights are the
// nodes' area shares (fit/node_weights.hpp) so a fine patch of mesh does not outvote a coarse
// one; no mean is removed, since a steady residual (the cycle mean) is itself a finding.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "loop/residual_field.hpp"

namespace finverse::loop {

struct ResidualModes {
  Eigen::VectorXd energy_fraction;  // [modes]
  Eigen::MatrixXd shape;            // [3 nv, modes], unit weighted norm
  Eigen::MatrixXd coefficient;      // [nf, modes]: a_m(t)
  double total_energy = 0;          // sum_m s_m^2 = sum_i,k w_i |r_ik|^2
};

// The leading `max_modes` modes (fewer when the matrix has fewer). weights: one per node (empty:
// all 1); zero-weight nodes (the prescribed root) get a zero shape. Throws InvalidInput on a
// weight count other than the field's node count or a negative weight.
ResidualModes residual_modes(const ResidualField& field, const Eigen::VectorXd& weights, int max_modes);

}  // namespace finverse::loop
