// One coupled time step of the 3-D flow and a shell (or shell + beam) structure whose wet surface is
// its triangulated mid-surface (seed paper section 2.3, steps 1-5; DESIGN.md 5.3): the operator H
// of the implicit coupling on x = [X; V], the wet nodes' displacement and velocity.
// evaluate(x) restores the flow to the step's start, places the closed thin body around the
// mid-surface at X_ref + X moving with V (acceleration (V - V^n) / dt, so H depends on x only),
// takes one flow step, hands the triangles' forces to the nodes (force exact, moment exact about
// any point: cfd/forces/nodal_loads.hpp), advances the structure and returns its wet [X; V].
// Generic: driven nodes (a pitching leading edge, a fin's root) follow their prescribed motion
// inside the structure model; this step only exchanges the wet surface.
// The flow sees either the closed thin body around the mid-surface (ghost cells) or the mid-surface
// itself as a zero-thickness sheet (FlowSolver::immerse_sheet; docs/studies/thin_surface.md),
// chosen by immerse(); with the sheet the markers' forces return to the nodes directly.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/thin_body.hpp"
#include "fem/coupled_structure.hpp"
#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi {

struct SurfaceStepRecord {
  long step = 0;
  double time = 0;                   // t^{n+1}
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // on the body [N]
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // about the moment centre [N m]
  double power = 0;                  // sum_i F_i . v_i at t^{n+1} [W]
  double interface_work = 0;         // the structure's W_I over the step [J]
  double transfer_mismatch = 0;      // max over the step's evaluations: |dF| / |F| and |dM| / (|F| L)
};

// The thin body's forces moved onto the mid-surface nodes, with both sides' totals.
struct SurfaceLoadTransfer {
  Eigen::Matrix3Xd loads;  // 3 x nodes [N]
  Eigen::Vector3d flow_force = Eigen::Vector3d::Zero(), flow_moment = Eigen::Vector3d::Zero();
  Eigen::Vector3d node_force = Eigen::Vector3d::Zero(), node_moment = Eigen::Vector3d::Zero();
  // max(|dF| / |F|, |dM| / (|F| length)).
  [[nodiscard]] double mismatch(double length) const;
};

// forces: per body triangle; nodes: 3 x node_count mid-surface positions at the same instant.
SurfaceLoadTransfer transfer_surface_loads(const cfd::ThinBody& body, const cfd::SurfaceForces& forces,
                                           const Eigen::Matrix3Xd& nodes, const Eigen::Vector3d& centre);
// The same for the flow's zero-thickness sheet: its last step's forces, the flow side's moment
// from the markers' forces at the markers.
SurfaceLoadTransfer transfer_sheet_loads(const cfd::FlowSolver& flow, double rho, const Eigen::Matrix3Xd& nodes,
                                         const Eigen::Vector3d& centre);

class SurfaceFlowStructureStep final : public CoupledStep {
 public:
  // flow: set up with a fixed time step dt; immerse() then places the body in it (before the
  // flow's initialise()); structure: dim 3, its wet nodes are the mid-surface nodes 0..n-1 in order
  // (n = body.node_count), time_step dt; mid: the mid-surface triangles; wet_reference: 3 x n;
  // rho: fluid density (the flow's pressure is kinematic); length: the moment mismatch's scale.
  // All referenced objects must outlive this one. Throws finverse::Error on mismatched sizes.
  SurfaceFlowStructureStep(cfd::FlowSolver& flow, fem::CoupledStructure& structure, const cfd::ThinBody& body,
                           std::vector<std::array<int, 3>> mid, Eigen::Matrix3Xd wet_reference, double rho,
                           double dt, Eigen::Vector3d moment_centre, double length);

  void begin_step(const StepInfo& info) override;
  void save() override;
  void restore() override;
  [[nodiscard]] Eigen::VectorXd evaluate(const Eigen::VectorXd& interface_motion) override;
  void accept(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) override;
  void resume(const Eigen::VectorXd& x_in) override;

  // The body at the mid-surface positions x0 in the flow: the closed thin body, or with `sheet`
  // the mid-surface as a zero-thickness sheet with those options.
  void immerse(const Eigen::Matrix3Xd& x0, const std::optional<cfd::SheetForcingOptions>& sheet = std::nullopt);
  // The body's state at the flow's next time level (positions, velocities, accelerations 3 x n).
  void place(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& a);
  // The loads of the flow's last step on the nodes at positions x.
  [[nodiscard]] SurfaceLoadTransfer transfer(const Eigen::Matrix3Xd& x) const;

  [[nodiscard]] InterfaceLayout layout() const;
  [[nodiscard]] const std::vector<SurfaceStepRecord>& records() const { return records_; }
  [[nodiscard]] const Eigen::Matrix3Xd& wet_loads() const { return loads_; }  // last evaluation [N]

  // The body's surface state for mid-surface positions, velocities and accelerations (3 x n each).
  [[nodiscard]] cfd::SurfaceState body_state(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                             const Eigen::Matrix3Xd& a) const;

 private:
  [[nodiscard]] std::string where() const;

  cfd::FlowSolver& flow_;
  fem::CoupledStructure& structure_;
  const cfd::ThinBody& body_;
  std::vector<std::array<int, 3>> mid_;
  Eigen::Matrix3Xd reference_;
  double rho_, dt_, length_;
  Eigen::Vector3d centre_;
  std::vector<cfd::StateArray> saved_flow_;
  Eigen::Matrix3Xd velocity_start_;
  StepInfo info_;
  Eigen::Matrix3Xd loads_;
  SurfaceStepRecord current_;
  double step_mismatch_ = 0;
  std::vector<SurfaceStepRecord> records_;
};

}  // namespace finverse::fsi
