// What the Turek-Hron run needs of its coupled step, whichever way the flag enters the flow: the
// closed body of ghost cells (flow_structure_step.hpp) or its wet surface as a zero-thickness
// sheet (sheet_flag_step.hpp; issue 44, goal 6). Per accepted step a StepRecord: body and flag
// forces, the interface power sum F_i . v_i [W/m], the structure's interface work over the step and
// the worst force / moment transfer mismatch.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

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
};

}  // namespace finverse::fsi::validation
