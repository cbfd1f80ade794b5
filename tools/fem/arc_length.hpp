// Static equilibrium path f_int(x) = f_fixed + lambda q traced by Crisfield's cylindrical
// arc-length method (Crisfield 1981, "A fast incremental/iterative solution procedure that
// handles snap-through", Computers & Structures 13:55-62; also Crisfield 1991, vol. 1, ch. 9).
//
// Unlike load control (static_solver.hpp) the load factor lambda is an unknown: each step
// satisfies the constraint |Delta u|_s^2 = Delta l^2 on the step's displacement increment, so the
// path goes through limit points (snap-through) where the tangent stiffness turns singular and
// then indefinite. Per corrector iteration two solves with the same factorised tangent:
//   K du_r = r (out-of-balance),  K du_t = q (reference load),  du = du_r + dlambda du_t,
// and dlambda is a root of the quadratic a1 dlambda^2 + a2 dlambda + a3 = 0 from the constraint
// (Crisfield 1981; cylindrical: no load term in the constraint, psi = 0). Of the two roots the one
// whose new increment makes the smallest angle with the current one is taken; complex roots cut
// the step. Predictor: dlambda = +-Delta l / |du_t|_s, its sign that of du_t . Delta u_prev (the
// angle criterion of Feng, Peric & Owen 1996, Comput. Struct. 58:479-485), so the path turns at
// limit points; the first step goes in the direction of initial_load_increment. No branch
// switching at bifurcation points.
// Step size: after a converged step Delta l *= sqrt(target_iterations / iterations) (Crisfield
// 1981), the factor clamped to [0.5, 2] and Delta l to [min, max]; a step that fails
// (no convergence in max_iterations, complex roots, non-finite or diverging residual, singular
// tangent) is retried with Delta l / 2, and below min_arc_length the solver throws NotConverged.
//
// |.|_s: translations divided by the model extent L_char plus rotations (radians), the same
// scaling as the increment criterion of static_solver.hpp. Rotational increments are summed as
// spins, which is what the constraint measures (a step is small).
// Loads: q = Model::reference_load() (the nodal loads); f_fixed = Model::external_load(time) -
// load_factor(time) q (gravity and the tabulated loads at `time`) is held fixed. Prescribed DOFs
// keep the values they have in the starting state. E(t) fields are evaluated at `time`.
// Convergence: as static_solver.hpp, |r_free| <= residual_tolerance * scale + round-off floor
// and |du|_s <= increment_tolerance, with scale = max(|f_ext_free|, |reactions|, |q_free|):
// the reference load enters the scale because a traced path crosses lambda = 0 (for a snapped-
// through arch, at zero load and zero reactions) where the other two vanish.
// Stops: after max_steps, or at the first step crossing stop_load_factor or the displacement
// stop; that last point is then corrected onto the stop value exactly (a Newton solve with lambda
// fixed, or with the displacement fixed as in Batoz & Dhatt 1979, IJNME 14:1262); if that
// fails the crossing point is kept.
// Errors: SingularMatrix (tangent at the starting state), NotConverged (Delta l below its
// minimum), InvalidInput (bad options, no reference load, NaN load) -- one line each.
#pragma once

#include <optional>
#include <vector>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/model.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem {

struct ArcLengthOptions {
  // Delta l of the first step. 0: Delta l = |initial_load_increment * K^-1 q|_s (the arc length of
  // a first load step of that size); the sign of initial_load_increment sets the direction.
  double initial_arc_length = 0;
  double initial_load_increment = 0.1;
  double min_arc_length = 0;  // 0: 1e-4 x initial
  double max_arc_length = 0;  // 0: 10 x initial
  int target_iterations = 4;
  int max_steps = 200;
  int max_iterations = 25;
  double residual_tolerance = 1e-8;
  double increment_tolerance = 1e-10;
  std::optional<double> stop_load_factor{};
  // Stops when the displacement (x - X) of translational global DOF stop_dof (6*node + 0..2)
  // crosses stop_displacement.
  int stop_dof = -1;
  double stop_displacement = 0;
  // Global DOFs whose values are recorded along the path: translations x - X, rotations the
  // component of the rotation vector log(R).
  std::vector<int> tracked_dofs{};
  double time = 0;  // time of the fixed loads and of the stiffness field
  SolverBackend backend = SolverBackend::cholmod;
  bool unsymmetric_tangent = false;  // as StaticOptions::unsymmetric_tangent
};

struct ArcLengthPoint {
  double load_factor = 0;
  std::vector<double> values;  // ArcLengthOptions::tracked_dofs, in that order
  int iterations = 0;          // 0 for the starting point
  double arc_length = 0;       // Delta l used for the step (0 for the starting point)
  double residual = 0;         // relative, at convergence
};

enum class ArcLengthStop { max_steps, load_factor, displacement };

struct ArcLengthResult {
  std::vector<ArcLengthPoint> path;  // starting point first, then every converged step
  int total_iterations = 0;
  int cutbacks = 0;
  ArcLengthStop stop = ArcLengthStop::max_steps;
  bool stop_corrected = false;  // the last point lies exactly on the stop value
};

class ArcLengthSolver {
 public:
  ArcLengthSolver(const Model& model, ArcLengthOptions options = {});

  // Traces the path from (state, lambda_begin), which must be in equilibrium; state ends at the
  // last point of the path.
  ArcLengthResult solve(NodalState& state, double lambda_begin);

  const Model& model() const { return model_; }
  const ArcLengthOptions& options() const { return opt_; }
  const DofMap& dofs() const { return dofs_; }
  const SparseSolver& linear_solver() const { return solver_; }

 private:
  // How dlambda is chosen in the corrector.
  enum class Constraint { arc, fixed_load, fixed_displacement };
  struct Corrector {
    int iterations = -1;  // -1: failed
    double residual = 0;
    bool singular = false;
  };
  // Corrector iterations from trial (increment du_step, load factor lam, both updated).
  Corrector correct(NodalState& trial, Eigen::VectorXd& du_step, double& lam, double arc,
                    Constraint constraint, double target);
  // One corrector step from the out-of-balance force r (newton_iteration.hpp): du = du_r + dlam du_t
  // with dlam from the constraint, applied to trial, du_step and lam; returns |du|_s, or nothing
  // when the step must be cut (singular tangent, which also sets `singular`; complex roots).
  std::optional<double> correction(const Eigen::VectorXd& r, NodalState& trial, Eigen::VectorXd& du_step,
                                   double& lam, double arc, Constraint constraint, double target, bool& singular);
  // Residual r = f_ext(lam) - f_int on the free DOFs after assembling at state; sets scale.
  Eigen::VectorXd residual(const NodalState& state, double lam, double& scale);
  double dot_s(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  double displacement(const NodalState& state, int global_dof) const;
  ArcLengthPoint point(const NodalState& state, double lam) const;

  const Model& model_;
  ArcLengthOptions opt_;
  DofMap dofs_;
  Assembler assembler_;
  SparseSolver solver_;
  Eigen::VectorXd weight2_;  // per free DOF: 1/L_char^2 (translation) or 1 (rotation)
  Eigen::VectorXd q_full_, q_free_;  // reference load q
  Eigen::VectorXd fixed_load_;       // f_fixed (full length)
  int stop_equation_ = -1;               // free equation of stop_dof
};

}  // namespace finverse::fem
