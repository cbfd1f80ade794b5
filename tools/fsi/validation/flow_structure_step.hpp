// One coupled time step of a 2-D flow and the elastic flag (seed paper section 2.3, steps 1-5;
// DESIGN.md 5.3) as the operator H of the implicit coupling on x = [X; V], the wet nodes'
// displacement and velocity. evaluate(x) restores the flow to the step's start, places the body at
// X_ref + X moving with V, accelerating with (V - V^n) / dt (V^n: last step's converged velocity,
// so H depends on x only), takes one flow step, hands the flag's traction to the wet nodes
// (fsi/interface_transfer.hpp: force and moment kept, mismatch measured) and advances the
// structure; H(x) is its wet [X; V]. All evaluations of a step use the cell kinds of its first
// iterate (FlowSolver::set_body_state's kinds_at), so H is continuous in x (a centre crossing the
// wall between iterations does not flip its cell; docs/studies/fsi_turek_hron.md section 7).
// Per accepted step a StepRecord (flag_coupled_step.hpp).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "fem/coupled_structure.hpp"
#include "fsi/interface_transfer.hpp"
#include "fsi/validation/flag_coupled_step.hpp"
#include "fsi/validation/flag_flow_body.hpp"

namespace finverse::fsi::validation {

class FlowStructureStep final : public FlagCoupledStep {
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
  void resume(const Eigen::VectorXd& x_in) override;

  [[nodiscard]] InterfaceLayout layout() const override;
  [[nodiscard]] const std::vector<StepRecord>& records() const override { return records_; }
  [[nodiscard]] const Eigen::Matrix2Xd& wet_loads() const override { return loads_; }
  // false: every evaluation classifies the cells at its own x (the jumping H, for comparison).
  void set_frozen_kinds(bool on) { frozen_kinds_ = on; }

 private:
  cfd::FlowSolver& flow_;
  fem::CoupledStructure& structure_;
  const FlagFlowBody& body_;
  WetSurface2D surface_;
  double rho_, dt_;
  std::vector<cfd::StateArray> saved_flow_;
  Eigen::Matrix2Xd velocity_start_;  // V^n (the converged wall velocity)
  bool frozen_kinds_ = true;
  std::optional<cfd::PolygonState> kinds_;  // the step's first iterate
  Eigen::Matrix2Xd loads_;
  StepRecord current_;
  double step_mismatch_ = 0;
  std::vector<StepRecord> records_;
};

}  // namespace finverse::fsi::validation
