// StaticSolver: static equilibrium f_int(x) = f_ext(lambda) by Newton-Raphson under load control.
//
// The load factor lambda goes from its start to its end value in steps; each step starts from
// the converged configuration, applies the change of the prescribed DOFs, and iterates with the
// (symmetrised, see assembly.hpp) consistent tangent: the iteration of newton_iteration.hpp.
// A step that moves prescribed DOFs first carries the free DOFs along with the linear response
// to that motion, from the tangent at the converged base (consistent predictor, predict_free). A
// step that does not converge within max_iterations, or whose residual becomes non-finite or grows
// by 1e6, is halved and retried (step cutting); after a converged step the step grows again (x1.5)
// up to the initial size.
// Converged when both
//   |r_free| <= residual_tolerance * max(|f_ext_free|, |f_reaction|) + round-off floor
//   |du| / L_char + |dtheta| <= increment_tolerance   (L_char: model extent)
// (round-off floor: roundoff_force_floor in assembly.hpp).
// Errors: SingularMatrix (unconstrained model), NotConverged (step below min_step),
// InvalidInput (NaN load, bad material) -- each with a one-line message.
#pragma once

#include <string>
#include <vector>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/model.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem {

struct StaticOptions {
  int steps = 10;               // initial number of equal load steps
  int max_iterations = 25;
  double residual_tolerance = 1e-8;
  double increment_tolerance = 1e-10;
  double min_step_fraction = 1e-4;  // smallest step, as a fraction of the initial step
  SolverBackend backend = SolverBackend::cholmod;
  // Full consistent tangent (not symmetrised) factorised by LU instead of its symmetric part by
  // Cholesky/LDL^T: needed under dead end moments, whose tangent keeps a skew part at equilibrium
  // (assembly.hpp). LU backend: umfpack, or sparse_lu if `backend` names it (umfpack is ~2.5x
  // faster per refactorisation, docs/studies/fem_sparse_solver.md).
  bool unsymmetric_tangent = false;
};

struct StaticStepInfo {
  double load_factor = 0;
  int iterations = 0;
  double residual = 0;  // relative, at convergence
};

struct StaticResult {
  std::vector<StaticStepInfo> steps;
  int total_iterations = 0;
  int step_cuts = 0;
  Eigen::VectorXd reaction;  // full length: f_int - f_ext at the prescribed DOFs, zero elsewhere
};

// Names an equation "node 3 rz" for error messages.
std::string describe_equation(const DofMap& dofs, int equation);
std::string describe_dof(int global_dof);

// Increment of the prescribed DOFs from one state to another, full length (zero elsewhere):
// translations as differences, rotations as spatial spins (NodalState::apply_increment).
Eigen::VectorXd prescribed_increment(const DofMap& dofs, const NodalState& from, const NodalState& to);

// Applies the prescribed values at time t2, given they were at t1 in `state` (see model.hpp).
void apply_prescribed(const Model& model, double t1, double t2, NodalState& state);

class StaticSolver {
 public:
  StaticSolver(const Model& model, StaticOptions options = {});

  // Solves from lambda_begin (state must be in equilibrium there, e.g. the reference state at 0)
  // to lambda_end. With base_offset (full length), the balance is
  // f_int(x) + base_offset = f_ext(lambda) instead: quasi_static_increment.hpp uses it to take
  // a base state as in equilibrium whether it is or not.
  StaticResult solve(NodalState& state, double lambda_begin, double lambda_end,
                     const Eigen::VectorXd* base_offset = nullptr);

  const Model& model() const { return model_; }
  const StaticOptions& options() const { return opt_; }

  const DofMap& dofs() const { return dofs_; }
  Assembler& assembler() { return assembler_; }
  const SparseSolver& linear_solver() const { return solver_; }

 private:
  // One Newton solve at load factor lam, starting from state (prescribed DOFs already applied).
  // Returns iterations used, or -1 on non-convergence (state then undefined).
  int newton(NodalState& state, double lam, const Eigen::VectorXd* offset, double& residual);

  // Linear predictor for a step that moves prescribed DOFs: with the tangent K at the converged
  // base `state`, the free DOFs of `trial` (prescribed DOFs already moved) get
  // du_f = -K_ff^-1 K_fp du_p. Without it only the prescribed nodes jump and the first Newton
  // iterate concentrates the whole increment in the elements next to them (a rigid 0.24 mm
  // root heave of the 50 um fin membrane took 225 iterations and drifted onto folded states).
  // Returns the factorisations used (0: nothing prescribed moved, or a singular base tangent).
  int predict_free(const NodalState& state, NodalState& trial, double lam);

  const Model& model_;
  StaticOptions opt_;
  DofMap dofs_;
  Assembler assembler_;
  SparseSolver solver_;
  double lchar_;
};

}  // namespace finverse::fem
