// One coupled time step of a 2-D flow and the elastic flag (seed paper section 2.3, steps 1-5;
// DESIGN.md 5.3; issue 32) as the operator H of the implicit coupling (fsi/implicit_coupling.hpp):
// x = [X; V], the wet nodes' displacement from the reference and their velocity, node by node.
//   evaluate(x): the flow is restored to the step's start, its body placed at t^{n+1} with the wet
//   nodes at X_ref + X moving with V, and the acceleration from the finite difference over the step
//   a = (V - V^n) / dt (V^n: the converged wall velocity of the previous step; the structure's own
//   acceleration would make H depend on the previous iterate, not only on x); one flow step; the
//   flag segments' traction samples (edge_traction) go to the wet nodes with the linear transfer
//   of fsi/interface_transfer.hpp (force and moment about the cylinder centre kept: the mismatch is
//   measured every evaluation); the structure advances over the step under those loads; H(x) is
//   its wet nodes' [X; V] at t^{n+1}.
// The cells' kinds (fluid / ghost / solid) of all evaluations of a step are those of its first
// iterate (FlowSolver::set_body_state's kinds_at), so that H is continuous in x: a cell centre
// crossing the wall between iterations does not flip the cell's kind (docs/studies/fsi_turek_hron.md
// section 7); the cells whose kind changes from step to step get the cleared/covered treatment once.
// Per accepted step a StepRecord: force on the whole body (cylinder + flag: drag, lift) and on the
// flag alone, the interface power sum_i F_i . v_i (structure side, N/m * m/s = W/m), the
// structure's interface work over the step, and the worst force / moment transfer mismatch.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cfd/flow/flow_solver.hpp"
#include "fem/coupled_structure.hpp"
#include "fsi/implicit_coupling.hpp"
#include "fsi/interface_transfer.hpp"
#include "fsi/validation/flag_flow_body.hpp"

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

class FlowStructureStep final : public CoupledStep {
 public:
  // flow: set up, with immerse_deforming(body.state(reference)) and initialise() done, fixed time
  // step dt; structure: its wet nodes in the body's order, dim 2, time_step dt. rho: fluid density
  // (the flow's pressure is kinematic). Both must outlive this object.
  FlowStructureStep(cfd::FlowSolver& flow, fem::CoupledStructure& structure, const FlagFlowBody& body, double rho,
                    double dt);

  void begin_step(const StepInfo& info) override;
  void save() override;
  void restore() override;
  [[nodiscard]] Eigen::VectorXd evaluate(const Eigen::VectorXd& interface_motion) override;
  void accept(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) override;

  [[nodiscard]] InterfaceLayout layout() const;
  [[nodiscard]] const std::vector<StepRecord>& records() const { return records_; }
  // Wet-node loads of the last evaluation, 2 x n_wet [N/m].
  [[nodiscard]] const Eigen::Matrix2Xd& wet_loads() const { return loads_; }
  // false: every evaluation classifies the cells at its own x (the jumping H, for comparison).
  void set_frozen_kinds(bool on) { frozen_kinds_ = on; }

 private:
  [[nodiscard]] std::string where() const;  // "fsi: step N (t = ...)", for participants' errors

  cfd::FlowSolver& flow_;
  fem::CoupledStructure& structure_;
  const FlagFlowBody& body_;
  WetSurface2D surface_;
  double rho_, dt_;
  std::vector<cfd::StateArray> saved_flow_;
  Eigen::Matrix2Xd velocity_start_;  // V^n (the converged wall velocity)
  bool frozen_kinds_ = true;
  std::optional<cfd::PolygonState> kinds_;  // the step's first iterate
  StepInfo info_;
  Eigen::Matrix2Xd loads_;
  StepRecord current_;
  double step_mismatch_ = 0;
  std::vector<StepRecord> records_;
};

}  // namespace finverse::fsi::validation
