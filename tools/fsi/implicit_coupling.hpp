// The implicit partitioned coupling of one time step (seed paper section 2.3, steps 1-5; DESIGN.md
// 5.3): the fixed point x = H(x) of the interface motion x = [X; V] (coupling_data.hpp), with
// H(x) = S(F(x)): the flow over the step with the surface at x -> surface loads -> the structure
// over the step under those loads -> its surface motion. Per step N:
//   1. predictor x^{N,1}: X^{N-1} + dt V^{N-1} and V^{N-1} (the paper's step 1; default), or linear
//      extrapolation 2 x^{N-1} - x^{N-2}, or the last state x^{N-1};
//   2. per iteration m: restore() the participants to the step's start, x_out = evaluate(x^{N,m});
//      stop when the convergence measure is met (convergence_measure.hpp); else
//      x^{N,m+1} = acceleration(x^{N,m}, x_out) (Aitken, IQN-ILS, constant relaxation);
//   3. the accepted state is the converged x_out (the structure's motion; the participants already
//      hold the state of that last evaluation, so nothing is recomputed).
// Failure: a residual growing for k consecutive iterations, or not finite -> CouplingDiverged;
// the iteration cap -> CouplingNotConverged; both restore() the participants to the step's start
// (the last good state) before throwing.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "fsi/acceleration.hpp"
#include "fsi/convergence_measure.hpp"
#include "fsi/coupling_data.hpp"

namespace finverse::fsi {

struct StepInfo {
  long step = 0;      // N, 1-based
  double time = 0.0;  // t^{N-1}, the step's start
  double dt = 0.0;
};

// The participants of the coupling (flow and structure together), as the loop sees them.
// Contract: evaluate(x) after restore() must depend only on x and the saved state (deterministic),
// so that the iterations of a step are evaluations of one operator H.
class CoupledStep {
 public:
  virtual ~CoupledStep() = default;
  // The step about to be computed; called once per step before save().
  virtual void begin_step(const StepInfo& /*info*/) {}
  // Keep the state at the start of the step (in memory: flow field, structure state, histories).
  virtual void save() = 0;
  // Put flow and structure back to the saved state; called before every evaluate(), the first too.
  virtual void restore() = 0;
  // H(x): advance flow and structure over the step with the surface motion x = [X; V]; return the
  // structure's surface motion [X; V] at the step's end (same layout).
  [[nodiscard]] virtual Eigen::VectorXd evaluate(const Eigen::VectorXd& interface_motion) = 0;
  // The step converged with input x_in and output x_out (the participants hold the state of that
  // evaluation): the place for outputs of the step.
  virtual void accept(const Eigen::VectorXd& /*x_in*/, const Eigen::VectorXd& /*x_out*/) {}
  // A restart (coupled_run.hpp): the last accepted input x_in before it, which accept() would have
  // kept (the wall's velocity at the next step's start); nothing is stepped or recorded.
  virtual void resume(const Eigen::VectorXd& /*x_in*/) {}
};

enum class Predictor { ConstantVelocity, Linear, Constant };

struct CouplingOptions {
  ConvergenceOptions convergence;
  int max_iterations = 50;
  int divergence_iterations = 4;  // residual growing this many iterations in a row: diverged (0: off)
  Predictor predictor = Predictor::ConstantVelocity;
  // At the iteration cap, instead of CouplingNotConverged: evaluate once more the iterate with the
  // smallest residual and accept that (StepStatistics::converged false), as preCICE moves on after
  // its max-iterations. For participants whose H(x) jumps (an immersed boundary whose cells change
  // between fluid and solid as the surface moves), where no iterate may meet the tolerance.
  bool accept_at_cap = false;
};

// The coupling of an immersed surface: stop at the relative or absolute interface tolerance or the
// cap, never on a growing residual (a surface crossing cells makes the residual jump), and accept
// the best iterate at the cap unless `strict`.
inline CouplingOptions immersed_coupling_options(double relative_tolerance, double absolute_tolerance,
                                                 int max_iterations, bool strict = false) {
  CouplingOptions co;
  co.convergence.relative_tolerance = relative_tolerance;
  co.convergence.absolute_tolerance = absolute_tolerance;
  co.max_iterations = max_iterations;
  co.divergence_iterations = 0;
  co.accept_at_cap = !strict;
  return co;
}

struct IterationReport {
  long step = 0;
  double time = 0.0;      // t^N, the end of the step
  int iteration = 0;      // m, 1-based
  double residual = 0.0;  // relative measure |x_out - x_in| / |x_out|
  double absolute = 0.0;  // |x_out - x_in|
  double omega = 0.0;     // the acceleration's last relaxation factor (1: quasi-Newton)
};

// One progress line: "step 12 (time 0.06): iteration 3, residual 1.23e-04, omega 0.31".
[[nodiscard]] std::string progress_line(const IterationReport& report);

// Per step, for fsi.h5 (issue 32): coupling iterations and the final residual.
struct StepStatistics {
  long step = 0;
  double time = 0.0;  // t^N
  int iterations = 0;
  double residual = 0.0;           // final relative measure
  double absolute_residual = 0.0;  // final |x_out - x_in|
  std::vector<double> residual_history;  // relative measure per iteration
  bool converged = false;
};

class CouplingDiverged : public Error {
 public:
  CouplingDiverged(const std::string& message, StepStatistics statistics)
      : Error(message), statistics(std::move(statistics)) {}
  StepStatistics statistics;
};

class CouplingNotConverged : public Error {
 public:
  CouplingNotConverged(const std::string& message, StepStatistics statistics)
      : Error(message), statistics(std::move(statistics)) {}
  StepStatistics statistics;
};

class ImplicitCoupling {
 public:
  // initial: the interface motion [X; V] at time t0 (X the displacement from the reference).
  ImplicitCoupling(InterfaceLayout layout, Eigen::VectorXd initial,
                   std::unique_ptr<Acceleration> acceleration, CouplingOptions options = {},
                   double t0 = 0.0);

  // Compute step N = steps() + 1 from time() to time() + dt; throws as said above.
  StepStatistics advance(CoupledStep& step, double dt);

  void set_progress(std::function<void(const IterationReport&)> progress) {
    progress_ = std::move(progress);
  }
  [[nodiscard]] const Eigen::VectorXd& state() const { return state_; }  // x^N accepted
  [[nodiscard]] const Eigen::VectorXd& previous_state() const { return previous_; }  // x^{N-1}
  // The input of the accepted iteration of step N (x_in, whose output x^N met the tolerance).
  [[nodiscard]] const Eigen::VectorXd& accepted_input() const { return accepted_input_; }
  // Continue a run from a checkpoint taken after step `steps` at `time` (state, previous_state and
  // accepted_input as they were then); the acceleration's carried state is restored separately.
  void restart(Eigen::VectorXd state, Eigen::VectorXd previous, Eigen::VectorXd accepted_input, double time,
               long steps);
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] long steps() const { return steps_; }
  [[nodiscard]] Acceleration& acceleration() { return *acceleration_; }
  [[nodiscard]] const InterfaceLayout& layout() const { return layout_; }

 private:
  [[nodiscard]] Eigen::VectorXd predict(double dt) const;

  InterfaceLayout layout_;
  Eigen::VectorXd state_;     // x^{N-1}
  Eigen::VectorXd previous_;  // x^{N-2} (empty before the second step)
  Eigen::VectorXd accepted_input_;  // x_in of step N-1's accepted iteration
  std::unique_ptr<Acceleration> acceleration_;
  CouplingOptions options_;
  ConvergenceMeasure measure_;
  double time_;
  long steps_ = 0;
  std::function<void(const IterationReport&)> progress_;
};

}  // namespace finverse::fsi
