// One coupled time step of the Turek-Hron flag entering the flow as its wet surface, a
// zero-thickness sheet (issue 44, goal 6; docs/studies/thin_surface.md, "Goal 6"), as the operator
// H of the implicit coupling on x = [X; V], the wet nodes' displacement and velocity. The cylinder
// stays a fixed ghost-cell body; the flag's wet nodes (lower clamp corner, lower edge, tip, upper
// edge, upper clamp corner: an open polyline whose ends sit on the cylinder) are the sheet's nodes,
// so no cell changes kind as the flag moves. evaluate(x) restores the flow to the step's start,
// sets the sheet's nodes to X_ref + X moving with V, takes one flow step and hands the sheet's
// nodal loads (FlowSolver::sheet_loads: conservative by construction) to the structure, whose wet
// [X; V] at the step's end is H(x). The body force is the cylinder's surface traction (less the
// arc the flag's root covers) plus the sheet's total.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/forces/surface_traction.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"
#include "fem/coupled_structure.hpp"
#include "fsi/validation/flag_coupled_step.hpp"

namespace finverse::fsi::validation {

class SheetFlagStep final : public FlagCoupledStep {
 public:
  // flow: set up, with the cylinder immersed (immerse(cylinder)), the sheet immersed without a
  // motion (immerse_sheet at wet_reference) and initialise() done, fixed time step dt; structure:
  // its wet nodes in wet_reference's order, dim 2, time_step dt. rho, nu: the fluid's density and
  // kinematic viscosity. flow and structure must outlive this object.
  SheetFlagStep(cfd::FlowSolver& flow, fem::CoupledStructure& structure, const cfd::TurekHronGeometry& geometry,
                const cfd::Polygon& cylinder, Eigen::Matrix2Xd wet_reference, double rho, double nu, double dt);

  void begin_step(const StepInfo& info) override;
  void save() override;
  void restore() override;
  [[nodiscard]] Eigen::VectorXd evaluate(const Eigen::VectorXd& interface_motion) override;
  void accept(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) override;

  [[nodiscard]] InterfaceLayout layout() const override;
  [[nodiscard]] const std::vector<StepRecord>& records() const override { return records_; }
  [[nodiscard]] const Eigen::Matrix2Xd& wet_loads() const override { return loads_; }

 private:
  [[nodiscard]] Eigen::Vector2d cylinder_force() const;

  cfd::FlowSolver& flow_;
  fem::CoupledStructure& structure_;
  cfd::TurekHronGeometry geometry_;
  cfd::SurfaceTraction cylinder_;
  Eigen::Matrix2Xd wet_reference_;
  double rho_, nu_, dt_;
  std::vector<cfd::StateArray> saved_flow_;
  Eigen::Matrix2Xd loads_;
  StepRecord current_;
  double step_mismatch_ = 0;
  std::vector<StepRecord> records_;
};

}  // namespace finverse::fsi::validation
