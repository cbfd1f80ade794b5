// The per-time-step implicit coupling loop (implicit_coupling.hpp; seed paper section 2.3).
#include "fsi/implicit_coupling.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace finverse::fsi {

namespace {

std::string step_text(long step, double time, double residual, int iterations) {
  std::ostringstream s;
  s.precision(6);
  s << "at step " << step << " (time " << time << "): residual " << residual << " after "
    << iterations << " iteration" << (iterations == 1 ? "" : "s");
  return s.str();
}

std::string format_number(double value) {
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

}  // namespace

std::string progress_line(const IterationReport& report) {
  char line[160];
  std::snprintf(line, sizeof line, "step %ld (time %.6g): iteration %d, residual %.2e, omega %.3g",
                report.step, report.time, report.iteration, report.residual, report.omega);
  return line;
}

ImplicitCoupling::ImplicitCoupling(InterfaceLayout layout, Eigen::VectorXd initial,
                                   std::unique_ptr<Acceleration> acceleration,
                                   CouplingOptions options, double t0)
    : layout_(layout),
      state_(std::move(initial)),
      acceleration_(std::move(acceleration)),
      options_(options),
      measure_(layout, options.convergence),
      time_(t0) {
  layout_.check(state_, "initial interface motion");
  if (!acceleration_) throw Error("fsi coupling: expected an acceleration, got none");
  if (options_.max_iterations < 1 || options_.divergence_iterations < 0) {
    throw Error("fsi coupling: expected max iterations >= 1 and divergence iterations >= 0, got " +
                std::to_string(options_.max_iterations) + " and " +
                std::to_string(options_.divergence_iterations));
  }
  if (options_.predictor == Predictor::ConstantVelocity && layout_.n_velocity == 0) {
    throw Error("fsi coupling: the constant-velocity predictor X + dt V expects a velocity block, "
                "the layout has none (use the linear or constant predictor)");
  }
}

void ImplicitCoupling::restart(Eigen::VectorXd state, Eigen::VectorXd previous, Eigen::VectorXd accepted_input,
                               double time, long steps) {
  layout_.check(state, "restart interface motion");
  if (previous.size() != 0) layout_.check(previous, "restart previous interface motion");
  if (accepted_input.size() != 0) layout_.check(accepted_input, "restart accepted input");
  if (steps < 0 || !std::isfinite(time))
    throw Error("fsi coupling: restart expects steps >= 0 and a finite time, got " + std::to_string(steps) + " and " +
                std::to_string(time));
  state_ = std::move(state);
  previous_ = std::move(previous);
  accepted_input_ = std::move(accepted_input);
  time_ = time;
  steps_ = steps;
}

Eigen::VectorXd ImplicitCoupling::predict(double dt) const {
  switch (options_.predictor) {
    case Predictor::ConstantVelocity: {
      Eigen::VectorXd x = state_;
      x.head(layout_.n_position) += dt * layout_.velocity(state_);
      return x;
    }
    case Predictor::Linear:
      return previous_.size() == 0 ? state_ : Eigen::VectorXd(2.0 * state_ - previous_);
    case Predictor::Constant:
      break;
  }
  return state_;
}

StepStatistics ImplicitCoupling::advance(CoupledStep& step, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw Error("fsi coupling: expected a positive time step, got " + std::to_string(dt));
  }
  StepStatistics stats;
  stats.step = steps_ + 1;
  stats.time = time_ + dt;
  step.begin_step({stats.step, time_, dt});
  step.save();
  acceleration_->reset_time_step();
  measure_.reset();

  Eigen::VectorXd x = predict(dt);
  Eigen::VectorXd best;  // accept_at_cap: the input with the smallest residual so far
  double best_residual = std::numeric_limits<double>::infinity();
  int growing = 0;
  for (int m = 1; m <= options_.max_iterations; ++m) {
    step.restore();
    Eigen::VectorXd x_out = step.evaluate(x);
    if (x_out.size() != layout_.size()) {
      step.restore();
      throw Error("fsi coupling: at step " + std::to_string(stats.step) +
                  " the participants returned an interface vector of size " +
                  std::to_string(x_out.size()) + ", expected " + std::to_string(layout_.size()));
    }
    const bool converged = measure_.measure(x, x_out);
    stats.iterations = m;
    stats.residual = measure_.relative();
    stats.absolute_residual = measure_.absolute();
    stats.residual_history = measure_.relative_history();
    if (progress_) {
      progress_({stats.step, stats.time, m, stats.residual, stats.absolute_residual,
                 acceleration_->last_omega()});
    }
    if (converged) {
      acceleration_->end_time_step(x, x_out);
      step.accept(x, x_out);
      stats.converged = true;
      accepted_input_ = x;
      previous_ = state_;
      state_ = std::move(x_out);
      time_ = stats.time;
      steps_ = stats.step;
      return stats;
    }
    if (options_.accept_at_cap && stats.absolute_residual < best_residual) {
      best_residual = stats.absolute_residual;
      best = x;
    }
    const auto& history = measure_.absolute_history();
    const bool finite = std::isfinite(stats.absolute_residual) && x_out.allFinite();
    growing = history.size() >= 2 && history.back() > history[history.size() - 2] ? growing + 1 : 0;
    if (!finite || (options_.divergence_iterations > 0 && growing >= options_.divergence_iterations)) {
      step.restore();
      throw CouplingDiverged(
          "coupling diverged " + step_text(stats.step, stats.time, stats.residual, m) +
              (finite ? ", growing for " + std::to_string(growing) + " iterations in a row"
                      : ", not finite"),
          stats);
    }
    if (m == options_.max_iterations && options_.accept_at_cap && best.size() == layout_.size()) {
      step.restore();
      Eigen::VectorXd x_out = step.evaluate(best);
      measure_.measure(best, x_out);
      stats.iterations = m + 1;
      stats.residual = measure_.relative();
      stats.absolute_residual = measure_.absolute();
      stats.residual_history = measure_.relative_history();
      acceleration_->end_time_step(best, x_out);
      step.accept(best, x_out);
      accepted_input_ = best;
      previous_ = state_;
      state_ = std::move(x_out);
      time_ = stats.time;
      steps_ = stats.step;
      return stats;  // converged stays false
    }
    if (m == options_.max_iterations) break;
    x = acceleration_->accelerate(x, x_out);
  }
  step.restore();
  throw CouplingNotConverged(
      "coupling did not converge " +
          step_text(stats.step, stats.time, stats.residual, stats.iterations) +
          " (the cap), expected a relative residual <= " +
          format_number(options_.convergence.relative_tolerance),
      stats);
}

}  // namespace finverse::fsi
