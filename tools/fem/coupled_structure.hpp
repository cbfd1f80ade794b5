// The structure as a participant of an implicit partitioned FSI coupling (seed paper sec. 2.3,
// steps 1-5; DESIGN.md sec. 5.3): within one coupling time step [t_n, t_n+1] the flow delivers
// forces on the wet-surface nodes, the structure advances over the step from the step's saved
// start state under those forces, and this repeats for every coupling iteration until the
// surface motion converges; accept() then ends the step.
//
// Loads. f_ext(t) = Model::external_load(t) + F_I(t), F_I the caller-set interface forces on the
// wet nodes' translations (dim components per node, stacked node by node). generalized-alpha
// (generalized_alpha.hpp) balances the forces at t_{n+1-alpha_f}, so the step applies exactly
//     F_I,{n+1-af} = (1 - alpha_f) F_I^{n+1} + alpha_f F_I^n,
// F_I^n the start load (the converged interface load of the previous step, or the initial one),
// F_I^{n+1} the argument of advance(). With k sub-steps the load is interpolated linearly in time,
// F_I(t_n + j h/k) = F_I^n + (j/k)(F_I^{n+1} - F_I^n), and each sub-step applies its own
// alpha_f-weighted pair. (The seed paper holds f^{N,m} constant over the step; the balance at
// t_{n+1-alpha_f} needs the start load too. rho_inf = 0 gives alpha_f = 0: only F_I^{n+1} acts.)
//
// Interface work. Over one step, summed over its sub-steps j:
//     W_I = sum_j (x_{j+1} - x_j) . [(1 - alpha_f) F_I,j+1 + alpha_f F_I,j]   (wet nodes)
// i.e. the displacement increment times the force the integrator actually balanced. With
// rho_inf = 1 (alpha_m = alpha_f = 1/2, beta = 1/4, gamma = 1/2: the trapezoidal rule) this is the
// trapezoidal work, and for a linear structure without moving supports
//     W_I + W_model = Delta(T + U) + D
// holds to round-off every step (multiply the balance by the increment: M (a_n + a_n+1)/2 .
// Delta u = Delta T and K (u_n + u_n+1)/2 . Delta u = Delta U). D is the Rayleigh damping work,
//     D = sum_j Delta q_j . [(1 - alpha_f) C_j+1 v_j+1 + alpha_f C_j v_j],  C v = a_M M v + a_K K v,
// with M, K at each end's configuration and Delta q the full increment (rotations: log(R1 R0^T)),
// as the integrator balances it; zero without damping. With rho_inf < 1 the identity leaves a
// remainder: the algorithm's dissipation plus (1/2 - alpha_f) sum Delta F . Delta x, first order in
// the step; W_I,trap = sum_j (x_{j+1} - x_j) . (F_I,j + F_I,j+1) / 2 is then the better (second-
// order) estimate of the physical work. For nonlinear elements f_int at the end points only
// approximates Delta U (second order in the step). W_model is the alpha_f-weighted expression for
// Model::external_load (gravity, nodal loads) on the translations (moments are not tracked).
//
// Save/restore. save() copies everything a step depends on: the DynamicState (configuration,
// velocities, accelerations, time), the integrator's memory (GeneralizedAlpha::Snapshot: the
// alpha-weighted old-step terms, the residual's force scale, the initialised flag) and the start
// load F_I^n. advance() always starts from the saved state, so repeated advances with the same
// load are bitwise identical and the coupling loop need not call restore() itself.
//
// Tangent reuse: every coupling iteration of a step starts Newton from the same predictor, so the
// first effective-stiffness matrix is the same each time; the integrator keeps that factorisation
// and reuses it when the matrix is bitwise equal (DynamicOptions::reuse_predictor_factorization,
// on here), which changes no result. The symbolic analysis is reused always (sparse_solver.hpp).
// Newton increments at position round-off count as zero (DynamicOptions::increment_roundoff_floor,
// on here): the loads of a ramped FSI start are tiny, and so are the first steps' increments.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "fem/assembly.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/model.hpp"

namespace finverse::fem {

struct CoupledStructureOptions {
  DynamicOptions dynamics;  // time_step: the coupling step; the integrator runs at time_step / substeps
  int substeps = 1;
  // A sub-step whose Newton solve fails is retried as two halves (the load still linear in time),
  // up to this many times nested (2^k shorter steps); 0: a failure ends the advance().
  int max_halvings = 0;
  int dim = 2;              // interface force / motion components per wet node (2: plane, 3: space)
  double start_time = 0;
};

// What one advance() did.
struct CoupledStepReport {
  int newton_iterations = 0;  // over all sub-steps
  int factorizations = 0;
  double residual = 0;        // of the last sub-step
  double interface_work = 0;  // W_I over the step (see above) [J, or J/m in plane strain]
  double interface_work_trapezoidal = 0;  // W_I,trap (equal to W_I at rho_inf = 1)
  double model_load_work = 0;  // W_model over the step
  double damping_work = 0;     // D over the step (>= 0 for a_M, a_K >= 0)
  int halvings = 0;            // failed sub-steps retried as two halves (max_halvings)
};

class CoupledStructure {
 public:
  // The model must outlive this object. Starts at rest in the reference configuration at
  // options.start_time under zero interface load (accelerations from equilibrium), and saves
  // nothing: call save() before the first advance(). Throws InvalidInput for a wet node out of
  // range or repeated, dim not in 1..3, substeps < 1, bad dynamics options.
  CoupledStructure(const Model& model, const CoupledStructureOptions& options,
                   std::vector<int> wet_nodes);

  // Restarts from `state` (the velocity must be full length) under the interface load F_I at
  // state.time; accelerations from equilibrium. Clears the saved state.
  void initialize(const DynamicState& state, const Eigen::VectorXd& interface_load);
  // The same from rest in the reference configuration at `t0`.
  void initialize(double t0, const Eigen::VectorXd& interface_load);

  // Start of a coupling step: the current state, integrator memory and interface load become the
  // state every advance() starts from.
  void save();
  // Back to the saved state (throws InvalidInput when nothing was saved).
  void restore();
  // Continue from a checkpoint of an accepted step (FSI restart): `state`, the integrator's memory
  // and the interface load become the current and the saved state exactly as save() after accept()
  // held them, so the run goes on bit for bit. Throws InvalidInput for sizes that do not fit.
  void restart(const DynamicState& state, const GeneralizedAlpha::Snapshot& integrator,
               const Eigen::VectorXd& interface_load);
  // One coupling step from the saved state to t_new = saved time + time_step with the interface
  // load F_I^{n+1} (dim * wet-node count entries). Throws InvalidInput before save(), for a wrong
  // size, a non-finite entry or a t_new off the step; NotConverged from the integrator.
  CoupledStepReport advance(double t_new, const Eigen::VectorXd& interface_load_new);
  // Ends the step: the advanced state and its load become the new start (saved). Throws
  // InvalidInput when no advance() happened since the last save().
  void accept();

  // Current state (after advance(): at t_new).
  const DynamicState& state() const { return state_; }
  double time() const { return state_.time; }
  const std::vector<int>& wet_nodes() const { return wet_; }
  int dim() const { return opt_.dim; }
  // Wet-node positions, velocities and accelerations, dim entries per node, in wet-node order.
  Eigen::VectorXd wet_positions() const;
  Eigen::VectorXd wet_velocities() const;
  Eigen::VectorXd wet_accelerations() const;
  // The interface load of the current state (the start load once accepted).
  const Eigen::VectorXd& interface_load() const { return load_; }
  // Kinetic and strain energy of the current state.
  double kinetic_energy();
  double strain_energy() const;
  // Full-length (6 per node) nodal force vector of a wet-node load (zero elsewhere).
  Eigen::VectorXd scatter(const Eigen::VectorXd& interface_load) const;

  GeneralizedAlpha& integrator() { return integrator_; }
  const CoupledStructureOptions& options() const { return opt_; }

 private:
  void check_load(const Eigen::VectorXd& f, const char* what) const;
  Eigen::VectorXd gather(const Eigen::VectorXd& full) const;

  // C v = a_M M v + a_K K v at the state (full length); the damping work's ingredient.
  Eigen::VectorXd damping_force(const DynamicState& s);
  // One sub-step of length h under the interface load going linearly from f_from to f_to, its
  // work added to `rep`; a failed Newton solve is retried as two halves while `halvings` > 0.
  struct SubstepStart {
    Eigen::VectorXd model_load, damping;  // Model::external_load and C v at the sub-step's start
  };
  void substep(double h, const Eigen::VectorXd& f_from, const Eigen::VectorXd& f_to, int halvings, SubstepStart& start,
               CoupledStepReport& rep);

  const Model& model_;
  CoupledStructureOptions opt_;
  std::vector<int> wet_;
  GeneralizedAlpha integrator_;
  std::unique_ptr<Assembler> damping_assembler_;  // only with Rayleigh damping
  DynamicState state_;
  Eigen::VectorXd load_;  // F_I at state_.time (wet-node vector)

  struct Saved {
    DynamicState state;
    GeneralizedAlpha::Snapshot integrator;
    Eigen::VectorXd load;
  };
  Saved saved_;
  bool has_saved_ = false;
  bool advanced_ = false;  // an advance() since the last save()
};

}  // namespace finverse::fem
