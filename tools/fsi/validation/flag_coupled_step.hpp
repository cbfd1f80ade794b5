// What the Turek-Hron run needs of its coupled step, whichever way the flag enters the flow: the
// closed body of ghost cells (flow_structure_step.hpp) or its wet surface as a zero-thickness
// sheet (sheet_flag_step.hpp; issue 44, goal 6). Per accepted step a StepRecord: body and flag
// forces, the interface power sum F_i . v_i [W/m], the structure's interface work over the step and
// the worst force / moment transfer mismatch.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "fem/coupled_structure.hpp"
#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi::validation {

struct StepRecord {
  long step = 0;
  double time = 0;                     // t^{n+1}
  std::array<double, 2> force{};       // whole body [N/m]: drag, lift
  std::array<double, 2> flag_force{};  // the flag's part [N/m]
  double power = 0;                    // sum_i F_i . v_i at t^{n+1} [W/m]
  double interface_work = 0;           // the structure's W_I over the step [J/m]
  double transfer_mismatch = 0;        // max over the step's evaluations: |dF| / |F| and |dM| / (|F| D)
};

class FlagCoupledStep : public CoupledStep {
 public:
  [[nodiscard]] virtual InterfaceLayout layout() const = 0;
  [[nodiscard]] virtual const std::vector<StepRecord>& records() const = 0;
  // Wet-node loads of the last evaluation, 2 x n_wet [N/m].
  [[nodiscard]] virtual const Eigen::Matrix2Xd& wet_loads() const = 0;

 protected:
  // The step's info kept for where(); a one-line error unless coupling, flow and structure share dt.
  void start_step(const StepInfo& info, double flow_dt, double dt) {
    info_ = info;
    if (std::abs(info.dt - dt) > 1e-12 * dt || std::abs(flow_dt - dt) > 1e-12 * dt)
      throw Error("fsi: step " + std::to_string(info.step) + " asks for dt = " + std::to_string(info.dt) +
                  " but flow and structure run at " + std::to_string(dt));
  }
  // "fsi: step N (t = ...)", for the participants' errors.
  [[nodiscard]] std::string where() const {
    return "fsi: step " + std::to_string(info_.step) + " (t = " + std::to_string(info_.time + info_.dt) + ")";
  }
  // Structure side of an evaluation: advance `structure` to t_new under the wet nodes' loads
  // (2 x n) and return its wet [X; V] at the step's end, X measured from `reference`; a failure
  // names the step (flag_coupled_step.cpp).
  [[nodiscard]] Eigen::VectorXd advance_structure(fem::CoupledStructure& structure, double t_new,
                                                  const Eigen::Matrix2Xd& loads, const Eigen::Matrix2Xd& reference,
                                                  fem::CoupledStepReport& report) const;
  // A wet surface of n nodes in 2-D: [X; V] in and out.
  [[nodiscard]] static InterfaceLayout wet_layout(Eigen::Index n) { return {2 * n, 2 * n}; }

  StepInfo info_;
};

}  // namespace finverse::fsi::validation
