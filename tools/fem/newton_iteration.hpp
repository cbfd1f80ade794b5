// The Newton iteration on the static balance f_int(x) = f_ext, shared by load control
// (static_solver.hpp) and the arc-length corrector (arc_length.hpp). Per iteration:
//   1. assemble the tangent at x and the out-of-balance force r = f_ext - f_int on the free DOFs;
//   2. stop as failed on a non-finite residual, on divergence (|r| above 1e6 max(|r_0|, 1) after
//      the third iteration) or after max_iterations corrections;
//   3. the caller's correction: solve with the tangent, apply du (the arc-length method also
//      moves lambda), and return the scaled norm |du|;
//   4. converged when |r| / scale <= residual_tolerance + floor / scale and |du| <= increment_tolerance,
//      floor being the round-off floor of the first tangent (roundoff_force_floor, assembly.hpp).
// The generalized-alpha step (generalized_alpha.cpp) runs its own loop; why is said there.
#pragma once

#include <functional>
#include <optional>

#include <Eigen/Core>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/nodal_state.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem {

struct NewtonTolerances {
  int max_iterations = 25;
  double residual_tolerance = 1e-8;
  double increment_tolerance = 1e-10;
};

struct NewtonOutcome {
  int iterations = -1;  // corrections to convergence; -1: failed (the iterate is then undefined)
  double residual = 0;  // relative residual of the last assembly
};

// residual(scale): assembles at the current iterate, returns r on the free DOFs and sets its scale.
// correct(r): applies one correction, returns its scaled norm, or nothing to stop as failed.
NewtonOutcome newton_iterations(const NewtonTolerances& tolerances, const Assembler& assembler,
                                const std::function<Eigen::VectorXd(double& scale)>& residual,
                                const std::function<std::optional<double>(const Eigen::VectorXd& r)>& correct);

// Assembles the tangent at `state` (stiffness field at `time`) and returns r = f_ext - f_int on the
// free DOFs. scale = max(|f_ext_free|, |reactions|, extra_scale, 1e-30): the reactions
// (f_int - f_ext at the prescribed DOFs) make the scale when the load is a prescribed displacement.
Eigen::VectorXd out_of_balance(Assembler& assembler, const NodalState& state, double time,
                               const Eigen::VectorXd& f_ext, double extra_scale, double& scale);

// |du| with translations divided by the model extent lchar and rotations in radians (du: free DOFs).
double scaled_increment_norm(const DofMap& dofs, const Eigen::VectorXd& du, double lchar);

// The factorisation of the tangent: `backend`, or an LU (umfpack, or sparse_lu if `backend` names
// it) for the full non-symmetric tangent.
SolverBackend tangent_backend(SolverBackend backend, bool unsymmetric_tangent);

}  // namespace finverse::fem
