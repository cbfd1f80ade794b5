// The structure's inertia in eq. (2) (issue 45, deliverable 3): the mass times the measured
// acceleration, a known load. In a dynamic motion the balance f_int(x(t)) + M a(t) = f_ext(t)
// holds at t and at t + dt, so the increment's balance gains the load change -M (a(t + dt) - a(t)),
// which the paper's eq. (2) drops (its bias against a dynamic truth: 15-19 % on the hybrid plate,
// docs/studies/fit_inertia.md).
//
// a: the target's central second difference, (x(s + h) - 2 x(s) + x(s - h)) / h^2 at its frame
// spacing h, translations only: the shell's rotary inertia (m t^2 / 36 per node) and the beams'
// are orders below the translational, and a rotation's second difference would amplify the 1-ring
// rotation fit's noise. M: the consistent mass at the base configuration.
#pragma once

#include <Eigen/Core>

#include "fem/model.hpp"
#include "fem/nodal_state.hpp"
#include "fit/target_motion.hpp"

namespace finverse::fit {

// Full-length load change -M (a(t + dt) - a(t)) (zero at rotations' rows only through M's
// structure). Throws InvalidInput naming target.source when the frames at t - h or t + dt + h
// fall outside the target's span.
Eigen::VectorXd inertial_load_change(const fem::Model& model, const fem::NodalState& base, const TargetMotion& target,
                                     double t, double dt);

}  // namespace finverse::fit
