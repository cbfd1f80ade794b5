// Implicit structural dynamics with the generalized-alpha method (Chung & Hulbert 1993,
// J. Appl. Mech. 60:371), parametrised by the high-frequency spectral radius rho_inf:
//   alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1),
//   gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4,
// with the balance  M a_{n+1-am} + C v_{n+1-af} + f_int,{n+1-af} = f_ext,{n+1-af}  where
// x_{n+1-a} = (1-a) x_{n+1} + a x_n (forces interpolated, as in Erlicher et al. 2002).
// rho_inf = 1 gives alpha_m = alpha_f = 1/2, gamma = 1/2, beta = 1/4: with consistent initial
// accelerations this reproduces the trapezoidal rule for linear systems, which conserves energy
// exactly; rho_inf < 1 damps the unresolved high frequencies (use ~0.8 for FSI).
//
// Rotations: the increment over a step is the spatial rotation vector dtheta with
// R_{n+1} = exp(dtheta) R_n; Newmark's relations are applied to it with spatial angular
// velocities/accelerations that are not transported between steps (the spatial form of Simo &
// Vu-Quoc 1988). Together with the configuration-dependent mass of the corotational beam without
// gyroscopic terms (corotational_beam.hpp), this is exact in the linear range and first-order
// consistent for large rotations; a fully consistent corotational inertia (Le, Battini & Hjiaj
// 2014) is not implemented.
// Damping: C = a_M M + a_K K_d, the options' plus the model's. K_d is each element's local
// stiffness acting on the rate of its deformation in the corotated frame (Kelvin-Voigt,
// Element::viscous_force): Rayleigh's a_K K in the linear range, but a rigid rotation is not damped
// and Newton keeps its rate, which a_K K(x) v with the current tangent lost (it damps the spin of
// a loaded element and its configuration derivative is not in the tangent;
// docs/studies/fin_dynamic_run.md, session 45).
// Prescribed DOFs move as prescribed; their velocities/accelerations follow from the same Newmark
// relations, so prescribed root motion enters consistently.
#pragma once

#include <vector>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/model.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem {

struct DynamicOptions {
  double time_step = 0;
  double spectral_radius = 1.0;  // rho_inf in [0, 1]
  double rayleigh_mass = 0;      // a_M [1/s]
  double rayleigh_stiffness = 0;  // a_K [s], on the corotated deformation rate
  int max_iterations = 20;
  double residual_tolerance = 1e-9;
  double increment_tolerance = 1e-9;  // relative to the step's increment
  SolverBackend backend = SolverBackend::cholmod;
  // Keep the factorisation of the first Newton iteration's matrix and reuse it when a later step
  // assembles a bitwise-equal one: the case of FSI coupling iterations, which all restart from the
  // same saved state and predictor (coupled_structure.hpp). Results are unchanged; costs a second
  // factorisation's memory and one comparison of the matrix values per step.
  bool reuse_predictor_factorization = false;
  // Treat Newton increments below the position round-off (10 eps sqrt(n) |x|max, scaled like the
  // increment norm) as zero in the increment test: a step that hardly moves (an FSI load ramp
  // starting from zero) otherwise cannot meet increment_tolerance relative to its own increment.
  bool increment_roundoff_floor = false;
  // The thin fin's slack membrane rotations (bending stiffness and rotary inertia both ~ h^3)
  // make the constant-acceleration predictor extrapolate a whirl and the reused factorisation
  // contract too slowly; both false: each step's Newton starts where the last step ended and
  // refactorises every iteration (issue 45, deliverable 2; docs/studies/fin_dynamic_run.md).
  bool predict_with_acceleration = true;
  bool modified_newton = true;  // keep the factorisation once the residual is below 1e-6
};

// The thin fin's iteration (docs/studies/fin_dynamic_run.md): no acceleration predictor and a
// new factorisation at every iteration; what `--full-newton` selects in fin-fem and fin-loop.
inline DynamicOptions with_full_newton(DynamicOptions options) {
  options.predict_with_acceleration = false;
  options.modified_newton = false;
  return options;
}

// options with the model's own Rayleigh damping (Model::set_rayleigh_damping) added to a_M, a_K:
// what every dynamic solver integrates with.
DynamicOptions with_model_damping(const Model& model, DynamicOptions options);

struct DynamicState {
  NodalState configuration;
  Eigen::VectorXd velocity;      // full length (6 per node)
  Eigen::VectorXd acceleration;  // full length
  double time = 0;
};

struct DynamicStepInfo {
  int iterations = 0;
  int factorizations = 0;
  double residual = 0;
};

class GeneralizedAlpha {
 public:
  // The integrator's memory between steps, besides the DynamicState: what a restart of a step
  // from a saved state needs (FSI coupling iterations) to reproduce it bit for bit.
  struct Snapshot {
    Eigen::VectorXd old_terms;
    double force_scale = 0;
    bool initialized = false;
  };

  GeneralizedAlpha(const Model& model, DynamicOptions options);

  // State at rest in the reference configuration at time t0.
  DynamicState reference_state(double t0 = 0) const;
  // Sets the free accelerations from equilibrium at the current state (M a = f_ext - f_int - C v),
  // and the prescribed ones from the prescribed functions.
  void initialize(DynamicState& state);
  DynamicStepInfo step(DynamicState& state);
  // The same with an added external load (full length, 6 per node, e.g. FSI interface forces) on
  // top of Model::external_load: for initialize() at state.time, for step() at the step's end
  // t_{n+1}. The load at the step's start is the one given to the previous step (or to
  // initialize), remembered in the old-step terms, so the balance at t_{n+1-alpha_f} sees
  // (1 - alpha_f) f_{n+1} + alpha_f f_n. An empty vector means zero (and gives bitwise the results
  // of the overloads without it).
  void initialize(DynamicState& state, const Eigen::VectorXd& added_load);
  DynamicStepInfo step(DynamicState& state, const Eigen::VectorXd& added_load);

  // The step of the following step() calls (> 0). The old-step terms do not depend on it, so a
  // step may be retried as shorter ones (fem::CoupledStructure's halving of a failed sub-step).
  void set_time_step(double h);
  double time_step() const { return opt_.time_step; }

  Snapshot snapshot() const { return {old_terms_, force_scale_, initialized_}; }
  void restore(const Snapshot& snapshot);

  double kinetic_energy(const DynamicState& state);
  double strain_energy(const DynamicState& state) const;

  double alpha_m() const { return am_; }
  double alpha_f() const { return af_; }
  double beta() const { return beta_; }
  double gamma() const { return gamma_; }
  const DofMap& dofs() const { return dofs_; }
  const SparseSolver& linear_solver() const { return solver_; }

 private:
  // alpha-weighted old-step terms: alpha_m M_n a_n + alpha_f (f_int,n + C_n v_n - f_ext,n)
  void store_old_terms(const DynamicState& state, const Eigen::VectorXd& added_load);
  void check_added_load(const Eigen::VectorXd& added_load) const;

  const Model& model_;
  DynamicOptions opt_;
  DofMap dofs_;
  Assembler assembler_;
  SparseSolver solver_;
  // reuse_predictor_factorization: the first iteration's matrix values and their factorisation.
  SparseSolver predictor_solver_;
  std::vector<double> predictor_values_;
  double am_, af_, beta_, gamma_;
  double lchar_;
  Eigen::VectorXd old_terms_;  // full length
  double force_scale_ = 0;     // largest force norm seen: the residual's reference
  bool initialized_ = false;
};

}  // namespace finverse::fem
