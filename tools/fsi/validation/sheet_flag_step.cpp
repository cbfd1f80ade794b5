// The Turek-Hron flag as a sheet in the coupled step; see sheet_flag_step.hpp.
#include "fsi/validation/sheet_flag_step.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "fsi/interface_transfer.hpp"

namespace finverse::fsi::validation {

SheetFlagStep::SheetFlagStep(cfd::FlowSolver& flow, fem::CoupledStructure& structure,
                             const cfd::TurekHronGeometry& geometry, const cfd::Polygon& cylinder,
                             Eigen::Matrix2Xd wet_reference, double rho, double nu, double dt)
    : flow_(flow),
      structure_(structure),
      geometry_(geometry),
      cylinder_(flow.grid(), *flow.immersed(), cylinder),
      wet_reference_(std::move(wet_reference)),
      rho_(rho),
      nu_(nu),
      dt_(dt) {
  const auto n = static_cast<std::size_t>(wet_reference_.cols());
  if (structure.wet_nodes().size() != n || structure.dim() != 2)
    throw Error("fsi: the structure's wet nodes (" + std::to_string(structure.wet_nodes().size()) + ", dim " +
                std::to_string(structure.dim()) + ") do not match the sheet's " + std::to_string(n) + " (dim 2)");
  if (!flow.sheet() || flow.sheet()->topology().nodes != n)
    throw Error("fsi: the flow has no sheet of the flag's " + std::to_string(n) + " wet nodes");
  if (!(dt > 0)) throw Error("fsi: the coupling time step must be > 0");
  loads_ = Eigen::Matrix2Xd::Zero(2, wet_reference_.cols());
}

InterfaceLayout SheetFlagStep::layout() const { return wet_layout(wet_reference_.cols()); }

void SheetFlagStep::begin_step(const StepInfo& info) {
  start_step(info, flow_.next_dt(), dt_);
  step_mismatch_ = 0;
}

void SheetFlagStep::save() {
  saved_flow_ = flow_.state();
  structure_.save();
}

void SheetFlagStep::restore() {
  flow_.restore(saved_flow_);
  structure_.restore();
}

// The cylinder's traction, without the arc inside the flag's root (x > xc, |y - yc| < thickness / 2):
// there the sheet model has the flag's enclosed fluid, not the flag, against the wall.
Eigen::Vector2d SheetFlagStep::cylinder_force() const {
  const cfd::SurfaceLoads L = cylinder_.evaluate(flow_.u(0), flow_.u(1), flow_.p(), nu_, rho_);
  const double a = 0.5 * geometry_.flag_thickness;
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < cylinder_.samples().size(); ++k) {
    const cfd::SurfaceSample& s = cylinder_.samples()[k];
    if (s.point[0] > geometry_.xc && std::abs(s.point[1] - geometry_.yc) < a) continue;
    f += Eigen::Vector2d(L.traction[k][0], L.traction[k][1]) * s.ds;
  }
  return f;
}

Eigen::VectorXd SheetFlagStep::evaluate(const Eigen::VectorXd& x) {
  const Eigen::Index n = wet_reference_.cols();
  const Eigen::Map<const Eigen::Matrix2Xd> X(x.data(), 2, n), V(x.data() + 2 * n, 2, n);
  const Eigen::Matrix2Xd position = wet_reference_ + X;
  double t_new = 0;
  try {
    cfd::SheetState next;
    for (Eigen::Index k = 0; k < n; ++k) {
      next.position.push_back({position(0, k), position(1, k), 0.0});
      next.velocity.push_back({V(0, k), V(1, k), 0.0});
    }
    flow_.set_sheet_state(std::move(next));
    t_new = flow_.step().time;
  } catch (const std::exception& e) {
    throw Error(where() + ": flow: " + e.what());
  }

  // Flow -> structure: the sheet's nodal loads (its markers' forces returned to the nodes by the
  // patches' weights, which keep the total).
  const cfd::SheetLoads sheet = flow_.sheet_loads(rho_);
  for (Eigen::Index k = 0; k < n; ++k) {
    loads_(0, k) = sheet.nodal[static_cast<std::size_t>(k)][0];
    loads_(1, k) = sheet.nodal[static_cast<std::size_t>(k)][1];
  }
  const Eigen::Vector2d flag_force(sheet.total[0], sheet.total[1]);
  const Eigen::Vector2d node_force = loads_.rowwise().sum();
  step_mismatch_ = std::max(step_mismatch_, (node_force - flag_force).norm() / std::max(flag_force.norm(), 1e-300));

  fem::CoupledStepReport report;
  const Eigen::VectorXd out = advance_structure(structure_, t_new, loads_, wet_reference_, report);
  const Eigen::VectorXd vs = out.tail(2 * n);

  current_.step = info_.step;
  current_.time = t_new;
  current_.flag_force = {flag_force.x(), flag_force.y()};
  current_.power = interface_power(loads_, Eigen::Map<const Eigen::Matrix2Xd>(vs.data(), 2, n));
  current_.interface_work = report.interface_work;
  return out;
}

// The flow holds the accepted evaluation's state: the cylinder's traction is sampled once per step.
void SheetFlagStep::accept(const Eigen::VectorXd&, const Eigen::VectorXd&) {
  structure_.accept();
  const Eigen::Vector2d body = cylinder_force() + Eigen::Vector2d(current_.flag_force[0], current_.flag_force[1]);
  current_.force = {body.x(), body.y()};
  current_.transfer_mismatch = step_mismatch_;
  records_.push_back(current_);
}

}  // namespace finverse::fsi::validation
