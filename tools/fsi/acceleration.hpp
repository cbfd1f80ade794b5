// The acceleration of the coupling fixed point x = H(x), H = S o F (flow then structure over one
// time step), in the style of preCICE's acceleration classes: given the input x_in of the current
// iteration and the structure's output x_out = H(x_in), return the next input. The loop
// (implicit_coupling.hpp) calls, per time step:
//   reset_time_step();  then per iteration  x_next = accelerate(x_in, x_out)  until converged;
//   then end_time_step(x_in, x_out) with the converged pair, which keeps what later steps reuse
//   (IQN-ILS's columns). The converged pair is not relaxed: the step's result is x_out.
// carried_state() / restore_carried_state(): what survives from one time step into the next (the
// reused columns, the last omega), as named flat arrays for checkpoints; a restart that restores
// it continues bit for bit.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace finverse::fsi {

class Acceleration {
 public:
  virtual ~Acceleration() = default;

  virtual void reset_time_step() = 0;
  [[nodiscard]] virtual Eigen::VectorXd accelerate(const Eigen::VectorXd& x_in,
                                                   const Eigen::VectorXd& x_out) = 0;
  virtual void end_time_step(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) = 0;
  // The relaxation factor of the last update (1 for a quasi-Newton update); for progress lines.
  [[nodiscard]] virtual double last_omega() const = 0;
  [[nodiscard]] virtual std::string name() const = 0;

  using CarriedState = std::map<std::string, std::vector<double>>;
  // Between time steps (after end_time_step); default: nothing is carried.
  [[nodiscard]] virtual CarriedState carried_state() const { return {}; }
  // Throws finverse::Error when the arrays do not fit this acceleration's layout.
  virtual void restore_carried_state(const CarriedState& /*state*/) {}
};

}  // namespace finverse::fsi
